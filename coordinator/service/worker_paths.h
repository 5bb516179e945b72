#pragma once
// A worker's failure reason reaches clients (a job's error, its events), but
// it names files as the worker sees them: under the worker's own --store-root,
// which may be spelled differently from the coordinator's (another mount, a
// relative path) and so escape ClientPaths. Before the coordinator stores a
// reason, the paths in it are rewritten (DESIGN.md §4: messages to clients
// carry no server path):
//   * a path through the job's store (or its partial directory) keeps the part
//     from the store on: ".../store/.job-1.wbk.partial/staging/x" becomes
//     "<store root>/.job-1.wbk.partial/staging/x";
//   * any other absolute path keeps its file name: "/var/x/y.obj" becomes
//     "<worker>/y.obj".
#include <string>

#include "absl/strings/string_view.h"

namespace wavebake {

std::string HideWorkerPaths(absl::string_view reason, const std::string& store_path);

}  // namespace wavebake
