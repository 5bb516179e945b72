// wavebake: thin entry point; every command lives in cli/cmd_*.cc.
#include "cli/commands.h"

int main(int argc, char** argv) { return wavebake::cli::Run(argc, argv); }
