// The memory a run may take and the refusal of one that would take more (io/memory_budget,
// io/machine_memory): the machine's memory read from /proc as the kernel writes it, the refusal's
// one line.
#include "tsmframe/io/memory_budget.hpp"

#include <gtest/gtest.h>

#include "tsmframe/io/machine_memory.hpp"
#include "tsmframe/io/system_error.hpp"

namespace {

using tsm::io::bytes_text;
using tsm::io::check_memory;
using tsm::io::MemoryBudget;

TEST(MachineMemory, FieldsOfProcMeminfoAndStatusInBytes) {
  const std::string meminfo = "MemTotal:       24731708 kB\nMemFree:        20444904 kB\nMemAvailable:   22890604 kB\n";
  EXPECT_EQ(tsm::io::kilobyte_field(meminfo, "MemAvailable"), 22890604.0 * 1024);
  EXPECT_EQ(tsm::io::kilobyte_field(meminfo, "MemTotal"), 24731708.0 * 1024);
  EXPECT_EQ(tsm::io::kilobyte_field(meminfo, "Mem"), -1.0);  // a whole name only
  EXPECT_EQ(tsm::io::kilobyte_field("VmPeak:\t  10000 kB\nVmSize:\t   9000 kB\n", "VmSize"), 9000.0 * 1024);
}

TEST(MachineMemory, TheMemoryControlGroupOfV1AndV2) {
  const auto v1 = tsm::io::memory_control_group("5:devices:/\n4:memory:/process_api/6ec5\n3:cpuset:/\n0::/\n");
  EXPECT_EQ(v1.path, "/process_api/6ec5");
  EXPECT_FALSE(v1.v2);
  const auto joint = tsm::io::memory_control_group("7:cpu,memory,blkio:/batch/job\n");  // controllers mounted together
  EXPECT_EQ(joint.path, "/batch/job");
  const auto v2 = tsm::io::memory_control_group("0::/user.slice/session-1.scope\n");
  EXPECT_EQ(v2.path, "/user.slice/session-1.scope");
  EXPECT_TRUE(v2.v2);
  EXPECT_EQ(tsm::io::memory_control_group("4:memoryless:/x\n").path, "");  // no such controller
}

TEST(MachineMemory, ThisMachineHasSome) {
  const tsm::io::MachineMemory m = tsm::io::machine_memory();
  EXPECT_GT(m.bytes, 1e6);
  EXPECT_FALSE(m.source.empty());
}

TEST(MemoryBudget, AStudysJobsShareTheMachine) {
  const MemoryBudget whole = tsm::io::memory_budget();
  const MemoryBudget half = tsm::io::memory_budget(2);
  EXPECT_NEAR(half.bytes, whole.bytes / 2, 0.05 * whole.bytes);  // read again: the machine moves on
  EXPECT_NE(half.description.find("among 2 study jobs"), std::string::npos) << half.description;
}

TEST(MemoryBudget, BytesAsText) {
  EXPECT_EQ(bytes_text(512), "512 B");
  EXPECT_EQ(bytes_text(48e3), "48 kB");
  EXPECT_EQ(bytes_text(57.3e6), "57 MB");
  EXPECT_EQ(bytes_text(20.44e9), "20.4 GB");
}

TEST(MemoryBudget, AnEstimateBeyondItIsRefusedInOneLineLargestPartFirst) {
  tsm::ModelCounts c;
  c.nodes = 1e7;
  c.elements = 1e7;
  const tsm::MemoryEstimate e = tsm::estimate_memory(c);
  EXPECT_NO_THROW(check_memory(e, {e.total(), "enough"}, "members"));
  try {
    check_memory(e, {2e9, "the machine's 2.0 GB available (MemAvailable)"}, "members");
    FAIL() << "not refused";
  } catch (const tsm::io::SystemError& error) {
    EXPECT_STREQ(error.what(),
                 "members: the run needs ~5.6 GB of memory (10,000,000 elements and 10,000,000 nodes 4.8 GB, the state of "
                 "1 step 800 MB, the program 6 MB), more than the machine's 2.0 GB available (MemAvailable)");
  }
}

}  // namespace
