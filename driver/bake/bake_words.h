#pragma once
// The bake parameters as people spell them (the command line's flags, and
// anything else that takes words): the words of core/bake/bake_param_words.h,
// parsed and validated (ParseBakeParamWords) into the BakeParams that every
// bake entry point of driver/ takes (EmbeddedBake, AutoBake, SubmitBake).
// Front ends include this, not core/, so that driver/ is all they reach.
#include "core/bake/bake_param_words.h"
