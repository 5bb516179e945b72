// The job views of `wavebake status` (driver/jobs/job_text.h): every field a user
// reads is there, the rate and ETA only when the coordinator knows them, and
// the JSON line is the whole message under its proto field names, numbers
// as numbers, phases as DONE.
#include "driver/jobs/job_text.h"

#include <gmock/gmock.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "driver/jobs/job_json.h"

namespace wavebake::driver {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

v1::Job BakingJob() {
  v1::Job job;
  job.set_id("7");
  job.set_phase(v1::PHASE_BAKING);
  job.set_store_path("cubes.wbk");
  job.set_tasks_done(3);
  job.set_tasks_total(12);
  job.set_tiles(10);
  job.set_groups(1);
  job.set_leased_tasks(2);
  job.set_rays_traced(123456789012);
  job.set_rays_estimate(987654321098);
  job.set_rays_per_second(-1);
  job.set_eta_seconds(-1);
  return job;
}

TEST(JobTextTest, DetailNamesEveryFieldAndOmitsUnknownRateAndEta) {
  const std::string text = JobDetailText(BakingJob());
  EXPECT_THAT(text, HasSubstr("phase      BAKING\n"));
  EXPECT_THAT(text, HasSubstr("store      cubes.wbk\n"));
  EXPECT_THAT(text, HasSubstr("3/12 done (10 tiles, 1 groups, 1 finalize), 2 leased"));
  EXPECT_THAT(text, HasSubstr("rays       123456789012 of ~987654321098\n"));
  EXPECT_THAT(text, Not(HasSubstr("Mrays/s")));
  EXPECT_THAT(text, Not(HasSubstr("ETA")));
  EXPECT_THAT(text, Not(HasSubstr("error")));
}

TEST(JobTextTest, DetailShowsRateEtaAndError) {
  v1::Job job = BakingJob();
  job.set_rays_per_second(2.5e6);
  job.set_eta_seconds(41.6);
  job.set_error("tile 3: out of memory");
  const std::string text = JobDetailText(job);
  EXPECT_THAT(text, HasSubstr(", 2.50 Mrays/s, ETA 42 s\n"));
  EXPECT_THAT(text, HasSubstr("error      tile 3: out of memory\n"));
}

TEST(JobTextTest, PhasesAsPeopleSayThem) {
  EXPECT_EQ(PhaseName(v1::PHASE_TRANSFORMING), "TRANSFORMING");
  EXPECT_EQ(PhaseLabel(v1::PHASE_BAKING), "bake tiles");
  EXPECT_EQ(PhaseLabel(v1::PHASE_TRANSFORMING), "transform columns");
  EXPECT_EQ(PhaseLabel(v1::PHASE_DONE), "done");
}

TEST(JobTextTest, ProgressLineOfAPhase) {
  v1::JobEvent e;
  e.set_phase(v1::PHASE_TRANSFORMING);
  e.set_phase_tasks_done(3);
  e.set_phase_tasks_total(12);
  e.set_rays_traced(8'000'000);
  e.set_rays_per_second(-1);
  e.set_eta_seconds(-1);
  EXPECT_EQ(ProgressText(e, 4.0),
            "transform columns  [#######.......................]  25% 3/12"
            "  2.0 Mrays/s  ETA --");
  e.set_rays_per_second(5e6);
  e.set_eta_seconds(41.6);
  EXPECT_THAT(ProgressText(e, 4.0), ::testing::EndsWith("5.0 Mrays/s  ETA 42s"));
}

TEST(JobTextTest, TableRowLinesUpUnderTheHeader) {
  const std::string header = JobTableHeader(), row = JobTableRow(BakingJob());
  EXPECT_EQ(header.find("PHASE"), row.find("BAKING"));
  EXPECT_EQ(header.find("STORE"), row.find("cubes.wbk"));
  EXPECT_EQ(row.back(), '\n');
}

// protobuf's own JSON printer is the oracle: the same keys and values, once
// its int64 strings are numbers and its enum names lose their prefix.
TEST(JobTextTest, JsonIsTheWholeMessageWithNumbersAndShortPhases) {
  v1::Job job = BakingJob();
  job.set_created_ms(1764790000123);
  job.mutable_request()->mutable_scene()->set_builtin("cubes-wall");
  job.mutable_request()->set_light_res(16);
  job.mutable_request()->set_seed(42);
  const std::string line = JobJson(job);
  EXPECT_EQ(line.find('\n'), line.size() - 1);
  std::string proto;
  google::protobuf::util::JsonPrintOptions options;
  options.always_print_primitive_fields = true;
  options.preserve_proto_field_names = true;
  ASSERT_TRUE(google::protobuf::util::MessageToJsonString(job, &proto, options).ok());
  nlohmann::json expected = nlohmann::json::parse(proto);
  ASSERT_EQ(expected["phase"], "PHASE_BAKING");
  expected["phase"] = "BAKING";
  for (const char* key : {"rays_traced", "rays_estimate", "bytes_written", "created_ms",
                          "started_ms", "finished_ms"}) {
    ASSERT_TRUE(expected[key].is_string()) << key;  // the proto mapping's int64 spelling
    expected[key] = std::stoll(expected[key].get<std::string>());
  }
  expected["request"]["seed"] = std::stoull(expected["request"]["seed"].get<std::string>());
  const nlohmann::json ours = nlohmann::json::parse(line);
  EXPECT_EQ(ours, expected) << ours.dump() << "\n" << expected.dump();
  EXPECT_EQ(ours["rays_traced"], 123456789012);
  EXPECT_EQ(ours["request"]["scene"], nlohmann::json({{"builtin", "cubes-wall"}}));
}

TEST(JobTextTest, EnumValuesLoseTheirTypesPrefixOnly) {
  EXPECT_EQ(EnumValueName(*v1::Phase_descriptor()->FindValueByNumber(v1::PHASE_DONE)), "DONE");
  EXPECT_EQ(EnumValueName(*v1::EventKind_descriptor()->FindValueByNumber(v1::EVENT_TASK_DONE)),
            "TASK_DONE");
  // TaskKind's values share no prefix: BAKE_TILE stays BAKE_TILE.
  EXPECT_EQ(EnumValueName(*v1::TaskKind_descriptor()->FindValueByNumber(v1::BAKE_TILE)),
            "BAKE_TILE");
}

}  // namespace
}  // namespace wavebake::driver
