// The per-tick path is real-time clean (STYLE rule 7): once the trace has room for its records,
// stepping devices through whole commands allocates nothing. Counted with a replaced global
// operator new that is active only inside the measured region.
#include <gtest/gtest.h>

#include <cstdlib>
#include <new>

#include "robot_fixture.hpp"

namespace {
bool gCounting = false;
size_t gAllocations = 0;
}  // namespace

// Every non-aligned form is replaced so allocation and release always pair up (ASan checks).
static void* countedAlloc(size_t size) noexcept {
  if (gCounting) ++gAllocations;
  return std::malloc(size ? size : 1);
}
void* operator new(size_t size) {
  if (void* p = countedAlloc(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](size_t size) {
  if (void* p = countedAlloc(size)) return p;
  throw std::bad_alloc();
}
void* operator new(size_t size, const std::nothrow_t&) noexcept { return countedAlloc(size); }
void* operator new[](size_t size, const std::nothrow_t&) noexcept { return countedAlloc(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }
void operator delete[](void* p, size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace virtcom::plant::test {
namespace {

const char* kCellYaml[][3] = {
    {"axis", "AxisX", "max_speed: 500 mm/s\nacceleration: 1 m/s^2\nmin_position: 0 mm\nmax_position: 1 m\n"},
    {"press", "Press", "stroke: 50 mm\nprograms:\n  1: { name: P, approach_time: 0.1 s, press_time: 0.2 s, force: 1 kN, sets: [pressed] }\n"},
    {"timed", "Clamp", "commands:\n  1: { name: LockInsert, duration: 0.3 s, sets: [insertLocked] }\n"},
    {"conveyor", "Belt", "speed: 100 mm/s\nlength: 1 m\nspawn_interval: 1 s\nend_fact: atEnd\nsensors:\n  s1: 500 mm\n"},
    {"sensor", "S", "fact: insertLocked\ndelay: 10 ms\n"},
};

TEST(NoAllocation, SteppingDevicesThroughCommandsDoesNotAllocate) {
  PlantRig rig;
  ASSERT_NE(rig.add("robot", "R1", kRobotYaml), nullptr);
  for (const auto& d : kCellYaml) ASSERT_NE(rig.add(d[0], d[1], d[2]), nullptr) << rig.renderedDiags();
  rig.prepare();
  rig.trace.activities.reserve(1000);
  rig.setFact("bearing1", true);
  rig.setFact("stud1", true);
  rig.setBool("Belt.run", true);
  rig.tick();

  const TagId robotCmd = rig.tagOf("R1.procedureNumber"), axisCmd = rig.tagOf("AxisX.targetPosition");
  const TagId pressCmd = rig.tagOf("Press.programNumber"), clampCmd = rig.tagOf("Clamp.programNumber");
  const TagId executes[] = {rig.tagOf("R1.execute"), rig.tagOf("AxisX.execute"), rig.tagOf("Press.execute"),
                            rig.tagOf("Clamp.execute")};
  gAllocations = 0;
  gCounting = true;
  for (int n : {1, 4, 7, 2, 8, 3, 99}) {  // moves, tools, grip/release, an unknown number
    rig.bus.setNumber(robotCmd, n);
    rig.bus.setNumber(axisCmd, n * 10.0);
    rig.bus.setNumber(pressCmd, 1);
    rig.bus.setNumber(clampCmd, 1);
    for (TagId e : executes) rig.bus.setBool(e, true);
    for (int i = 0; i < 4000; ++i) rig.tick();
    for (TagId e : executes) rig.bus.setBool(e, false);
    rig.tick();
  }
  gCounting = false;
  EXPECT_EQ(gAllocations, 0u);
  EXPECT_GE(rig.trace.activities.size(), 7u * 4);
}

}  // namespace
}  // namespace virtcom::plant::test
