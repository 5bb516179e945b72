// process_* numbers from /proc: the parser against a hand-written
// /proc/pid/stat line (proc(5) field numbers, a command with spaces and a
// ')'), and this process's live numbers against independent sources:
// getrusage(2) for CPU time and peak resident size, an extra open file for
// the descriptor count, the clock for the start time.
#include "web/process_metrics.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>

namespace wavebake::web {
namespace {

TEST(ProcessMetricsTest, ParsesProcStatFields) {
  // Fields 1..24: pid (comm) state ppid pgrp session tty tpgid flags minflt
  // cminflt majflt cmajflt utime=250 stime=50 cutime cstime priority nice
  // threads itrealvalue starttime=1000 vsize=8192000 rss=300.
  const std::string stat =
      "42 (a b) c) S 1 42 42 0 -1 4194560 10 0 0 0 250 50 0 0 20 0 3 0 1000 8192000 300 "
      "18446744073709551615";
  absl::StatusOr<ProcessStats> p = ParseProcStat(stat, 100, 4096, 1'700'000'000);
  ASSERT_TRUE(p.ok()) << p.status();
  EXPECT_DOUBLE_EQ(p->cpu_seconds, 3.0);
  EXPECT_DOUBLE_EQ(p->start_time_seconds, 1'700'000'010.0);
  EXPECT_EQ(p->virtual_bytes, 8192000);
  EXPECT_EQ(p->resident_bytes, 300 * 4096);
  EXPECT_FALSE(ParseProcStat("42 (x) S 1 2", 100, 4096, 0).ok());
  EXPECT_FALSE(ParseProcStat("no command", 100, 4096, 0).ok());
}

TEST(ProcessMetricsTest, LiveNumbersAgreeWithIndependentSources) {
  // Some CPU time to measure.
  volatile double sink = 0;
  for (int i = 0; i < 20'000'000; ++i) sink = sink + i * 1e-9;
  absl::StatusOr<ProcessStats> before = ReadProcessStats();
  ASSERT_TRUE(before.ok()) << before.status();
  rusage u{};
  ASSERT_EQ(getrusage(RUSAGE_SELF, &u), 0);
  const double rusage_cpu =
      u.ru_utime.tv_sec + u.ru_utime.tv_usec * 1e-6 + u.ru_stime.tv_sec + u.ru_stime.tv_usec * 1e-6;
  // /proc counts in clock ticks (1/100 s here), getrusage in microseconds.
  EXPECT_NEAR(before->cpu_seconds, rusage_cpu, 0.05);
  EXPECT_GT(before->resident_bytes, 0);
  EXPECT_LE(before->resident_bytes, u.ru_maxrss * 1024 + 4096 * 64);
  const double now =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  EXPECT_LE(before->start_time_seconds, now);
  EXPECT_GT(before->start_time_seconds, now - 24 * 3600.0);

  const int fd = open("/proc/self/stat", O_RDONLY);
  ASSERT_GE(fd, 0);
  absl::StatusOr<ProcessStats> after = ReadProcessStats();
  close(fd);
  ASSERT_TRUE(after.ok());
  EXPECT_EQ(after->open_fds, before->open_fds + 1);
  EXPECT_GT(after->max_fds, after->open_fds);
}

}  // namespace
}  // namespace wavebake::web
