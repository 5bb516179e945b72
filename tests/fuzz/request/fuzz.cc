// What a client sends the coordinator, validated as Submit validates it
// (proto/bake_request.h NormalizeBakeRequest), plus the id parsers every RPC
// runs (job, worker and lease ids). Properties beyond "no crash": a request
// that normalizes normalizes to itself again, turns into BakeParams, and
// those params survive ToBakeRequest; a lease id that parses formats back to
// the same text, and every error is INVALID_ARGUMENT naming its field.
#include "coordinator/scheduling/lease_id.h"
#include "coordinator/service/job_service.h"
#include "core/bake/bake_params_io.h"
#include "proto/bake_request.h"
#include "storage/store/params_json.h"
#include "tests/fuzz/fuzz_util.h"

namespace wavebake::fuzz {

std::vector<std::string> Seeds() {
  std::vector<std::string> seeds;
  BakeParams p;
  v1::BakeRequest r = ToBakeRequest(p);
  r.mutable_scene()->set_builtin("builtin:cubes-wall");
  seeds.push_back(r.SerializeAsString());
  p.light_res = 64;
  p.layout = "hilbert:128x64";
  p.column_terms = 17;
  p.bits = 11;
  p.row_filter = WaveletFilter::kDaub4;
  r = ToBakeRequest(p);
  r.mutable_scene()->mutable_uploaded()->set_sha256(std::string(64, 'a'));
  r.mutable_scene()->mutable_uploaded()->set_file_name("../bunny.obj");
  r.set_output_name("a/b.wbk");
  r.set_max_attempts(5);
  seeds.push_back(r.SerializeAsString());
  r.set_layout("camera:0x64");
  r.set_light_res(33);
  seeds.push_back(r.SerializeAsString());
  return seeds;
}

}  // namespace wavebake::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace wavebake;
  using fuzz::Require;
  const std::string text(reinterpret_cast<const char*>(data), size);

  // The id parsers take the raw bytes.
  v1::JobId id;
  id.set_id(text);
  absl::StatusOr<int64_t> job = ParseJobId(id);
  Require(job.ok() ? *job > 0 : absl::IsInvalidArgument(job.status()), "job id");
  if (std::optional<LeaseKey> key = ParseLeaseId(text))
    Require(ParseLeaseId(FormatLeaseId(*key)) == key, "lease id round trip");

  v1::BakeRequest request;
  if (!request.ParseFromString(text)) return 0;
  v1::BakeRequest normal = request;
  const absl::Status s = NormalizeBakeRequest(normal);
  if (!s.ok()) {
    Require(absl::IsInvalidArgument(s), "refusals are INVALID_ARGUMENT");
    Require(s.message().find(':') != absl::string_view::npos, "the message names a field");
    return 0;
  }
  const std::string& out = normal.output_name();
  Require(out.find('/') == std::string::npos && !out.starts_with("."),
          "an output name stays inside the store root");
  v1::BakeRequest again = normal;
  Require(NormalizeBakeRequest(again).ok(), "a normal request normalizes");
  Require(again.SerializeAsString() == normal.SerializeAsString(), "normalizing is idempotent");
  absl::StatusOr<BakeParams> params = ToBakeParams(normal);
  Require(params.ok(), "a normal request has params");
  Require(ValidateBakeParams(*params).ok(), "its params are valid");
  v1::BakeRequest rebuilt = ToBakeRequest(*params);  // carries no scene
  *rebuilt.mutable_scene() = normal.scene();
  absl::StatusOr<BakeParams> back = ToBakeParams(rebuilt);
  Require(back.ok() && ToJson(*back) == ToJson(*params), "params round trip");
  return 0;
}
