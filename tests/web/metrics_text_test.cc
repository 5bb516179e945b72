// /metrics in the Prometheus text format 0.0.4, checked by a strict parser
// written from the format's specification (prometheus.io, "Exposition
// formats") and the naming conventions ("Metric and label naming"): each
// family announced once by HELP then TYPE before its samples and its samples
// together; names and label names of the allowed characters; counters named
// *_total and gauges not; no label called job or instance (Prometheus' own
// target labels); no series twice; histogram buckets cumulative and ending
// at le="+Inf" with the count. And by promtool's `check metrics` when
// Debian's prometheus package is installed. The values are those of the
// snapshot; the lease histogram files each latency into the first bucket
// whose bound is not below it.
#include "web/metrics_text.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace wavebake::web {
namespace {

// name{labels} -> value, the TYPE of each family and the labels of samples.
struct Parsed {
  std::map<std::string, std::string> samples;
  std::map<std::string, std::string> types;
  std::set<std::string> label_names;
  std::vector<std::string> errors;
};

// The family a sample belongs to: histogram samples carry a suffix.
std::string FamilyOf(const std::string& name, const std::map<std::string, std::string>& types) {
  for (const char* suffix : {"_bucket", "_sum", "_count"}) {
    const std::string s(suffix);
    if (name.size() > s.size() && name.ends_with(s)) {
      const std::string base = name.substr(0, name.size() - s.size());
      auto it = types.find(base);
      if (it != types.end() && (it->second == "histogram" || it->second == "summary")) return base;
    }
  }
  return name;
}

Parsed Parse(const std::string& text) {
  static const std::regex kName("[a-zA-Z_:][a-zA-Z0-9_:]*");
  static const std::regex kSample(R"(([a-zA-Z_:][a-zA-Z0-9_:]*)(\{(.*)\})? (\S+))");
  static const std::regex kLabel(R"re(([a-zA-Z_][a-zA-Z0-9_]*)="((?:[^"\\\n]|\\[\\"n])*)")re");
  Parsed p;
  if (text.empty() || text.back() != '\n') p.errors.push_back("text does not end in a newline");
  std::istringstream in(text);
  std::string line, helped, current;
  std::set<std::string> closed;  // families whose samples have ended
  while (std::getline(in, line)) {
    if (line.rfind("# HELP ", 0) == 0) {
      helped = line.substr(7, line.find(' ', 7) - 7);
      if (!std::regex_match(helped, kName)) p.errors.push_back("bad name: " + helped);
      continue;
    }
    if (line.rfind("# TYPE ", 0) == 0) {
      std::istringstream t(line.substr(7));
      std::string name, type, rest;
      t >> name >> type >> rest;
      if (name != helped) p.errors.push_back("TYPE without its HELP just before: " + name);
      if (p.types.contains(name)) p.errors.push_back("family twice: " + name);
      if (!std::set<std::string>{"counter", "gauge", "histogram", "summary", "untyped"}.contains(
              type) ||
          !rest.empty())
        p.errors.push_back("bad TYPE line: " + line);
      if (type == "counter" && !name.ends_with("_total"))
        p.errors.push_back("counter without _total: " + name);
      if (type != "counter" && name.ends_with("_total"))
        p.errors.push_back(type + " named like a counter: " + name);
      p.types[name] = type;
      if (!current.empty()) closed.insert(current);
      current = name;
      continue;
    }
    std::smatch m;
    if (!std::regex_match(line, m, kSample)) {
      p.errors.push_back("not a sample line: " + line);
      continue;
    }
    const std::string name = m[1], labels = m[3], value = m[4];
    const std::string family = FamilyOf(name, p.types);
    if (!p.types.contains(family)) p.errors.push_back("sample before its TYPE: " + line);
    if (family != current || closed.contains(family))
      p.errors.push_back("sample apart from its family: " + line);
    // Labels: name="value" separated by commas, each name once.
    std::set<std::string> seen;
    std::string rest = labels;
    while (!rest.empty()) {
      std::smatch l;
      if (!std::regex_search(rest, l, kLabel, std::regex_constants::match_continuous)) {
        p.errors.push_back("bad labels: " + line);
        break;
      }
      const std::string label = l[1];
      if (!seen.insert(label).second) p.errors.push_back("label twice: " + line);
      if (label.rfind("__", 0) == 0) p.errors.push_back("reserved label: " + line);
      if (label == "job" || label == "instance")
        p.errors.push_back("label collides with a target label: " + line);
      p.label_names.insert(label);
      rest = l.suffix();
      if (!rest.empty()) {
        if (rest[0] != ',') {
          p.errors.push_back("bad label separator: " + line);
          break;
        }
        rest.erase(0, 1);
      }
    }
    char* end = nullptr;
    (void)std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0') p.errors.push_back("value not a number: " + line);
    const std::string key = m[2].matched ? name + "{" + labels + "}" : name;
    if (!p.samples.emplace(key, value).second) p.errors.push_back("series twice: " + key);
  }
  return p;
}

SchedulerSnapshot Example() {
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
      {.id = 7, .phase = Phase::kBaking, .tasks_done = 2, .tasks_total = 9, .leased_tasks = 2},
      // A finished job a snapshot might still carry: summed by phase only.
      {.id = 6, .phase = Phase::kDone, .tasks_done = 5, .tasks_total = 5}};
  LatencyHistogram h;
  for (double seconds : {0.00005, 0.0001, 0.0003, 0.02, 5.0}) h.Observe(seconds);
  s.lease_latency = h.Read();
  return s;
}

ProcessStats ExampleProcess() {
  return {.cpu_seconds = 1.5,
          .resident_bytes = 1 << 20,
          .virtual_bytes = 1 << 24,
          .open_fds = 12,
          .max_fds = 1024,
          .start_time_seconds = 1.7e9};
}

TEST(MetricsTextTest, FamiliesValuesAndHistogram) {
  const ProcessStats process = ExampleProcess();
  const Parsed p = Parse(MetricsText(Example(), &process));
  EXPECT_THAT(p.errors, ::testing::IsEmpty());
  EXPECT_EQ(p.types.at("wavebake_lease_latency_seconds"), "histogram");
  EXPECT_EQ(p.types.at("wavebake_tasks_completed_total"), "counter");
  EXPECT_EQ(p.types.at("wavebake_workers_registered_total"), "counter");
  EXPECT_EQ(p.types.at("wavebake_job_tasks"), "gauge");
  EXPECT_EQ(p.samples.at("wavebake_tasks_leased_total{kind=\"bake_tile\"}"), "5");
  EXPECT_EQ(p.samples.at("wavebake_tasks_completed_total{kind=\"finalize\"}"), "1");
  EXPECT_EQ(p.samples.at("wavebake_tasks_failed_total{kind=\"bake_tile\"}"), "1");
  EXPECT_EQ(p.samples.at("wavebake_jobs{phase=\"done\"}"), "2");
  EXPECT_EQ(p.samples.at("wavebake_jobs{phase=\"baking\"}"), "1");
  EXPECT_EQ(p.samples.at("wavebake_jobs{phase=\"failed\"}"), "0");
  EXPECT_EQ(p.samples.at("wavebake_rays_traced_total"), "123456789");
  EXPECT_EQ(p.samples.at("wavebake_workers_alive"), "3");
  EXPECT_EQ(p.samples.at("wavebake_workers_registered_total"), "4");
  EXPECT_EQ(p.samples.at("wavebake_job_tasks_done{job_id=\"7\"}"), "2");
  EXPECT_EQ(p.samples.at("wavebake_job_tasks{job_id=\"7\"}"), "9");
  EXPECT_EQ(p.samples.at("wavebake_job_tasks_leased{job_id=\"7\"}"), "2");
  EXPECT_FALSE(p.samples.contains("wavebake_job_tasks{job_id=\"6\"}"));  // finished
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

TEST(MetricsTextTest, BuildInfoAndProcessMetrics) {
  const ProcessStats process = ExampleProcess();
  const Parsed p = Parse(MetricsText(Example(), &process));
  EXPECT_THAT(p.errors, ::testing::IsEmpty());
  int build_info = 0;
  for (const auto& [key, value] : p.samples) {
    if (key.rfind("wavebake_build_info{", 0) != 0) continue;
    ++build_info;
    EXPECT_EQ(value, "1");
    EXPECT_THAT(key, ::testing::ContainsRegex(R"(version="[0-9]+\.[0-9]+\.[0-9]+")"));
    EXPECT_THAT(key, ::testing::HasSubstr("revision=\""));
  }
  EXPECT_EQ(build_info, 1);
  EXPECT_EQ(p.types.at("process_cpu_seconds_total"), "counter");
  EXPECT_EQ(p.samples.at("process_cpu_seconds_total"), "1.5");
  EXPECT_EQ(p.samples.at("process_resident_memory_bytes"), "1048576");
  EXPECT_EQ(p.samples.at("process_open_fds"), "12");
  EXPECT_EQ(p.samples.at("process_max_fds"), "1024");
  EXPECT_EQ(p.samples.at("process_start_time_seconds"), "1700000000");
  // Without process numbers (none readable) the families are left out whole.
  EXPECT_FALSE(Parse(MetricsText(Example())).types.contains("process_open_fds"));
}

// The strict parser must fail what it is there to catch.
TEST(MetricsTextTest, ParserRejectsConventionBreaks) {
  const std::string head = "# HELP a_total x\n# TYPE a_total counter\n";
  EXPECT_THAT(Parse(head + "a_total{job=\"1\"} 1\n").errors, ::testing::SizeIs(1));
  EXPECT_THAT(Parse("# HELP a x\n# TYPE a counter\na 1\n").errors, ::testing::SizeIs(1));
  EXPECT_THAT(Parse("# HELP a_total x\n# TYPE a_total gauge\na_total 1\n").errors,
              ::testing::SizeIs(1));
  EXPECT_THAT(Parse(head + "a_total 1\na_total 2\n").errors, ::testing::SizeIs(1));
  EXPECT_THAT(Parse(head + "a_total x\n").errors, ::testing::SizeIs(1));
  EXPECT_THAT(Parse(head + "a_total 1").errors, ::testing::SizeIs(1));
}

// promtool (Debian's prometheus package) parses and lints the text.
TEST(MetricsTextTest, PromtoolCheckMetrics) {
  if (!std::filesystem::exists("/usr/bin/promtool")) GTEST_SKIP() << "no /usr/bin/promtool";
  const ProcessStats process = ExampleProcess();
  const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "metrics.txt";
  std::ofstream(file) << MetricsText(Example(), &process);
  const std::string cmd = "/usr/bin/promtool check metrics < '" + file.string() + "' 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buf[256];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) output.append(buf, n);
  const int rc = pclose(pipe);
  std::filesystem::remove(file);
  EXPECT_EQ(rc, 0) << output;
  EXPECT_EQ(output, "");
}

}  // namespace
}  // namespace wavebake::web
