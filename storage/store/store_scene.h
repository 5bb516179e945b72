#pragma once
// Where this machine finds the scene a store was baked from. A store names
// its scene as every machine would (attrs "scene": builtin:NAME, or the
// scene file's name, with its content hash in attrs "scene_hash"), never by
// where one machine kept it; older stores recorded a path.
#include <filesystem>
#include <string>

namespace wavebake {

// builtin:NAME stays itself. A file name is looked for as given (relative to
// the working directory, or a path), then beside the store, then in each
// directory of $WAVEBAKE_SCENE_PATH (':'-separated); the first that exists
// is returned, else the name as given (loading it then fails, naming it).
// The caller checks the content hash where it matters (runtime/reference/eval.h).
std::string LocateStoreScene(const std::string& recorded, const std::filesystem::path& store);

// What a store records for a scene loaded from `spec`: builtin:NAME, or the
// file's name without its directory.
std::string RecordedSceneName(const std::string& spec);

}  // namespace wavebake
