// vm::CompiledHandoff: the one-shot handoff of machine code from a background compile to the
// scan thread (tiered execution, `--backend auto`).
#include "vm/compiled_handoff.hpp"

#include <gtest/gtest.h>

#include <thread>

using namespace virtcom;

namespace {

TEST(CompiledHandoff, NotReadyUntilPublished) {
  vm::CompiledHandoff handoff;
  EXPECT_FALSE(handoff.readyAfter(0));
  EXPECT_FALSE(handoff.readyAfter(1000));
  EXPECT_FALSE(handoff.published());
  EXPECT_EQ(handoff.code(), nullptr);
  auto code = std::make_shared<vm::CompiledCode>();
  handoff.publish(code);
  EXPECT_TRUE(handoff.readyAfter(0));
  EXPECT_TRUE(handoff.published());
  EXPECT_EQ(handoff.code(), code);
}

TEST(CompiledHandoff, HeldUntilTheAskedScan) {
  vm::CompiledHandoff handoff;
  handoff.holdUntilScan(5);
  handoff.publish(std::make_shared<vm::CompiledCode>());
  EXPECT_FALSE(handoff.readyAfter(0));
  EXPECT_FALSE(handoff.readyAfter(4));
  EXPECT_TRUE(handoff.readyAfter(5));
  EXPECT_TRUE(handoff.readyAfter(6));
}

// Published from another thread while this one polls as the scan loop does: once seen ready,
// the code read is the one published (run under the sanitizer build for the memory order).
TEST(CompiledHandoff, PublishedFromAnotherThread) {
  vm::CompiledHandoff handoff;
  auto code = std::make_shared<vm::CompiledCode>();
  code->entries.resize(3);
  std::thread publisher([&] { handoff.publish(code); });
  uint64_t polls = 0;
  while (!handoff.readyAfter(polls)) ++polls;
  const auto seen = handoff.code();
  ASSERT_NE(seen, nullptr);
  EXPECT_EQ(seen->entries.size(), 3u);
  publisher.join();
}

}  // namespace
