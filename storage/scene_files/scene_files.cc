#include "storage/scene_files/scene_files.h"

#include <system_error>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"

namespace wavebake {
namespace {

namespace fs = std::filesystem;

// Absolute and without "." or ".." parts, so that containment is a prefix
// test on path components (lexical: the confined root holds only what the
// server put there, so no link inside it was made by a client).
fs::path Normal(const fs::path& p) {
  std::error_code ec;
  fs::path n = fs::absolute(p, ec).lexically_normal();
  if (n.has_filename() || n == n.root_path()) return n;
  return n.parent_path();  // "dir/" → "dir"
}

class LocalFiles final : public SceneFiles {
 public:
  absl::StatusOr<fs::path> Resolve(const fs::path& from, std::string_view reference,
                                   std::string* warning) const override {
    if (reference.empty()) return absl::InvalidArgumentError("is empty");
    const std::string why = UnsafeReference(reference);
    if (!why.empty() && warning != nullptr)
      *warning = absl::StrCat("'", std::string(reference), "' ", why,
                              ": a remote job refuses it (an uploaded scene refers only to files "
                              "uploaded with it, by relative path)");
    const fs::path p{std::string(reference)};
    return p.is_absolute() ? p : from.parent_path() / p;
  }
  std::optional<fs::path> Open(const fs::path& path) const override { return path; }
  std::string Name(const fs::path& path) const override { return path.string(); }
  std::string Scrub(std::string message) const override { return message; }
};

class ConfinedFiles final : public SceneFiles {
 public:
  explicit ConfinedFiles(fs::path root) : root_(Normal(root)) {}

  absl::StatusOr<fs::path> Resolve(const fs::path& from, std::string_view reference,
                                   std::string*) const override {
    if (const std::string why = UnsafeReference(reference); !why.empty())
      return absl::InvalidArgumentError(
          absl::StrCat("'", std::string(reference), "' ", why,
                       ": an uploaded scene refers only to files uploaded with it, by relative "
                       "path"));
    const std::optional<fs::path> path = Open(from.parent_path() / std::string(reference));
    std::error_code ec;
    if (!path || !fs::is_regular_file(*path, ec))
      return absl::InvalidArgumentError(
          absl::StrCat("'", std::string(reference), "' was not uploaded with the scene"));
    return *path;
  }

  std::optional<fs::path> Open(const fs::path& path) const override {
    const fs::path p = Normal(path);
    const fs::path rel = p.lexically_relative(root_);
    if (rel.empty() || rel == "." || *rel.begin() == "..") return std::nullopt;
    return p;
  }

  std::string Name(const fs::path& path) const override {
    const fs::path rel = Normal(path).lexically_relative(root_);
    if (rel.empty() || *rel.begin() == "..") return path.filename().string();
    return rel.generic_string();
  }

  std::string Scrub(std::string message) const override {
    const std::string root = root_.string();
    absl::StrReplaceAll({{root + "/", ""}, {root, "."}}, &message);
    return message;
  }

 private:
  fs::path root_;
};

}  // namespace

std::string UnsafeReference(std::string_view reference) {
  if (reference.empty()) return "is empty";
  const fs::path p{std::string(reference)};
  if (p.is_absolute() || p.has_root_name() || p.has_root_directory()) return "is an absolute path";
  for (const fs::path& part : p)
    if (part == "..") return "leaves the scene's directory (\"..\")";
  return "";
}

std::unique_ptr<SceneFiles> LocalSceneFiles() { return std::make_unique<LocalFiles>(); }

std::unique_ptr<SceneFiles> ConfinedSceneFiles(std::filesystem::path root) {
  return std::make_unique<ConfinedFiles>(std::move(root));
}

}  // namespace wavebake
