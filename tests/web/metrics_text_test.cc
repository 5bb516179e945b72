// /metrics in the Prometheus text format 0.0.4: each family announced once by
// HELP and TYPE before its samples, counters named *_total, histogram buckets
// cumulative and ending at le="+Inf" with the count; the values those of the
// snapshot. The lease histogram files each latency into the first bucket
// whose bound is not below it.
#include "web/metrics_text.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <sstream>

namespace wavebake::web {
namespace {

using ::testing::HasSubstr;

// name{labels} -> value, and the TYPE of each family, parsed line by line.
struct Parsed {
  std::map<std::string, std::string> samples;
  std::map<std::string, std::string> types;
  std::vector<std::string> errors;
};

Parsed Parse(const std::string& text) {
  Parsed p;
  std::istringstream in(text);
  std::string line;
  std::set<std::string> helped;
  while (std::getline(in, line)) {
    if (line.rfind("# HELP ", 0) == 0) {
      helped.insert(line.substr(7, line.find(' ', 7) - 7));
      continue;
    }
    if (line.rfind("# TYPE ", 0) == 0) {
      std::istringstream t(line.substr(7));
      std::string name, type;
      t >> name >> type;
      if (!helped.contains(name)) p.errors.push_back("TYPE before HELP: " + name);
      if (p.types.contains(name)) p.errors.push_back("family twice: " + name);
      p.types[name] = type;
      continue;
    }
    const size_t space = line.rfind(' ');
    const std::string key = line.substr(0, space);
    const std::string name = key.substr(0, key.find('{'));
    std::string family = name;
    for (const char* suffix : {"_bucket", "_sum", "_count"}) {
      const std::string s(suffix);
      if (family.size() > s.size() && family.ends_with(s) &&
          p.types.contains(family.substr(0, family.size() - s.size()))) {
        family = family.substr(0, family.size() - s.size());
      }
    }
    if (!p.types.contains(family)) p.errors.push_back("sample before TYPE: " + key);
    if (p.types[family] == "counter" && !family.ends_with("_total"))
      p.errors.push_back("counter without _total: " + family);
    p.samples[key] = line.substr(space + 1);
  }
  return p;
}

TEST(MetricsTextTest, FamiliesValuesAndHistogram) {
  SchedulerSnapshot s;
  s.tasks.leased = {5, 3, 1};
  s.tasks.completed = {4, 3, 1};
  s.tasks.failed = {1, 0, 0};
  s.tasks.expired = {0, 0, 0};
  s.jobs_by_phase[static_cast<int>(Phase::kDone) - 1] = 2;
  s.jobs_by_phase[static_cast<int>(Phase::kBaking) - 1] = 1;
  s.rays_traced = 123456789;
  s.workers_alive = 3;
  s.workers_registered = 4;
  s.workers_excluded = 1;
  s.jobs = {
      {.id = 7, .phase = Phase::kBaking, .tasks_done = 2, .tasks_total = 9, .leased_tasks = 2}};
  LatencyHistogram h;
  for (double seconds : {0.00005, 0.0001, 0.0003, 0.02, 5.0}) h.Observe(seconds);
  s.lease_latency = h.Read();

  const Parsed p = Parse(MetricsText(s));
  EXPECT_THAT(p.errors, ::testing::IsEmpty());
  EXPECT_EQ(p.types.at("wavebake_lease_latency_seconds"), "histogram");
  EXPECT_EQ(p.types.at("wavebake_tasks_completed_total"), "counter");
  EXPECT_EQ(p.samples.at("wavebake_tasks_leased_total{kind=\"bake_tile\"}"), "5");
  EXPECT_EQ(p.samples.at("wavebake_tasks_completed_total{kind=\"finalize\"}"), "1");
  EXPECT_EQ(p.samples.at("wavebake_tasks_failed_total{kind=\"bake_tile\"}"), "1");
  EXPECT_EQ(p.samples.at("wavebake_jobs{phase=\"done\"}"), "2");
  EXPECT_EQ(p.samples.at("wavebake_jobs{phase=\"baking\"}"), "1");
  EXPECT_EQ(p.samples.at("wavebake_jobs{phase=\"failed\"}"), "0");
  EXPECT_EQ(p.samples.at("wavebake_rays_traced_total"), "123456789");
  EXPECT_EQ(p.samples.at("wavebake_workers_alive"), "3");
  EXPECT_EQ(p.samples.at("wavebake_job_tasks_done{job=\"7\"}"), "2");
  EXPECT_EQ(p.samples.at("wavebake_job_tasks_total{job=\"7\"}"), "9");
  // 0.00005 and 0.0001 are ≤ 0.0001; 0.0003 ≤ 0.0005; 0.02 ≤ 0.025; 5 s only ≤ +Inf.
  const std::string b = "wavebake_lease_latency_seconds_bucket{le=\"";
  EXPECT_EQ(p.samples.at(b + "0.0001\"}"), "2");
  EXPECT_EQ(p.samples.at(b + "0.00025\"}"), "2");
  EXPECT_EQ(p.samples.at(b + "0.0005\"}"), "3");
  EXPECT_EQ(p.samples.at(b + "0.01\"}"), "3");
  EXPECT_EQ(p.samples.at(b + "0.025\"}"), "4");
  EXPECT_EQ(p.samples.at(b + "1\"}"), "4");
  EXPECT_EQ(p.samples.at(b + "+Inf\"}"), "5");
  EXPECT_EQ(p.samples.at("wavebake_lease_latency_seconds_count"), "5");
  EXPECT_NEAR(std::stod(p.samples.at("wavebake_lease_latency_seconds_sum")), 5.02045, 1e-6);
}

}  // namespace
}  // namespace wavebake::web
