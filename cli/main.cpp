// wavebake: thin entry point; every command lives in cli/commands.*.
#include "cli/app.h"

int main(int argc, char** argv) { return wavebake::cli::Run(argc, argv); }
