#include "driver/relight/tree_export.h"

#include <span>

#include "absl/strings/str_cat.h"
#include "runtime/relight/sample_rows.h"
#include "runtime/relight/store_relight.h"
#include "storage/files/atomic_file.h"
#include "storage/store/store_reader.h"

namespace wavebake::driver {
namespace {

absl::Status Write(const std::filesystem::path& path, const void* data, size_t bytes) {
  return AtomicWriteFile(path, std::span(static_cast<const std::byte*>(data), bytes));
}

}  // namespace

absl::StatusOr<TreeSource> OpenTreeSource(const std::filesystem::path& store) {
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  if (!info.ok()) return info.status();
  if (absl::Status s = RequireCubeDomain(*info); !s.ok()) return s;
  // The trees are the diffuse T's rows (Boulton §4.5 integrates L against
  // the transfer function); Haar rows because the tree is the Haar basis's.
  if (info->params.transport != Transport::kDiffuse)
    return absl::FailedPreconditionError(
        "store: transport is visibility; wavelet-tree export takes diffuse stores");
  if (info->params.row_filter != WaveletFilter::kHaar)
    return absl::FailedPreconditionError("store: row_filter is not haar; the trees are Haar trees");
  absl::StatusOr<SampleSet> samples = ReadSamples(store);
  if (!samples.ok()) return samples.status();
  absl::StatusOr<CompressedColumns> columns = ReadTransport(store);
  if (!columns.ok()) return columns.status();
  return TreeSource{*std::move(samples), *std::move(columns)};
}

absl::StatusOr<WaveletTreeTextures> WaveletTreesOf(const TreeSource& source,
                                                   const WaveletTreeOptions& options) {
  absl::StatusOr<SampleRows> rows = SampleRows::Decode(source.columns);
  if (!rows.ok()) return rows.status();
  return BuildWaveletTrees(*rows, source.samples, options);
}

absl::StatusOr<WaveletTreeTextures> StoreWaveletTrees(const std::filesystem::path& store,
                                                      const WaveletTreeOptions& options) {
  absl::StatusOr<TreeSource> source = OpenTreeSource(store);
  if (!source.ok()) return source.status();
  return WaveletTreesOf(*source, options);
}

absl::StatusOr<nlohmann::json> ExportWaveletTrees(const std::filesystem::path& store,
                                                  const std::filesystem::path& out,
                                                  const WaveletTreeOptions& options) {
  absl::StatusOr<WaveletTreeTextures> t = StoreWaveletTrees(store, options);
  if (!t.ok()) return t.status();
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  if (!info.ok()) return info.status();
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) return absl::InvalidArgumentError(absl::StrCat("out: cannot create ", out.string()));
  const nlohmann::json header = WaveletTreeHeader(
      *t, {{"store", std::filesystem::absolute(store).lexically_normal().string()},
           {"scene_hash", info->scene_hash},
           {"store_format", info->attrs.value("format", "")}});
  if (absl::Status s = Write(out / "line.bin", t->line.data(), t->line.size()); !s.ok()) return s;
  if (absl::Status s = Write(out / "blocks.bin", t->blocks.data(), t->blocks.size() * 4); !s.ok())
    return s;
  if (absl::Status s = Write(out / "cells.bin", t->cells.data(), t->cells.size() * 4); !s.ok())
    return s;
  if (absl::Status s = AtomicWriteText(out / "header.json", header.dump(2) + "\n"); !s.ok())
    return s;
  return header;
}

}  // namespace wavebake::driver
