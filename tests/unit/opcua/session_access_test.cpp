// What a session's identity may do: a read-only session's Write is BadUserAccessDenied and its
// UserAccessLevel has no CurrentWrite; a read-write session writes. The handlers are called
// directly on the ADS test table (tests/unit/ads/ads_test_support.hpp).
#include <gtest/gtest.h>

#include "../ads/ads_test_support.hpp"
#include "proto/opcua/node_ids.hpp"
#include "proto/opcua/services.hpp"

namespace virtcom::proto::opcua {
namespace {

using Bytes = std::vector<uint8_t>;

const NodeId kCount = NodeId::str(ids::kPlcNamespace, "|var|virtcom.Application.MAIN.count");

class SessionAccessTest : public ::testing::Test {
 protected:
  SessionAccessTest() : table_(ads::testing::makeTable()), core_(table_, ServerConfig{}) {
    core_.publish(Bytes(64, 0));
    session_ = core_.createSession(1, 10'000, "s", 0);
    session_->activated = true;
  }

  // The one status of a Write of MAIN.count := 5.
  uint32_t writeCount() {
    Bytes request, response;
    Writer w(request);
    w.i32(1);
    encode(w, kCount);
    w.u32(13);  // Value
    w.nullString();
    DataValue v;
    v.hasValue = true;
    v.value = Variant::scalar(Scalar(int16_t{5}));
    encode(w, v);
    ServiceContext ctx{core_, 1, session_, 0};
    Reader in(request);
    Writer out(response);
    EXPECT_EQ(handleWrite(ctx, in, out), 0u);
    Reader r(response);
    uint32_t count = 0, status = 0xFFFFFFFF;
    EXPECT_TRUE(r.u32(count) && count == 1 && r.u32(status));
    return status;
  }

  // The Byte value of one attribute of MAIN.count, read through the Read service.
  uint8_t readByteAttribute(uint32_t attribute) {
    Bytes request, response;
    Writer w(request);
    encode(w, 0.0);
    w.u32(3);  // no timestamps
    w.i32(1);
    encode(w, kCount);
    w.u32(attribute);
    w.nullString();
    encode(w, QualifiedName{});
    ServiceContext ctx{core_, 1, session_, 0};
    Reader in(request);
    Writer out(response);
    EXPECT_EQ(handleRead(ctx, in, out), 0u);
    // Results: count, DataValue mask 0x01, Variant mask Byte (3), the byte.
    EXPECT_GE(response.size(), 7u);
    EXPECT_EQ(response[4], 0x01);
    EXPECT_EQ(response[5], 3);
    return response.size() >= 7 ? response[6] : 0xFF;
  }

  ads::SymbolTable table_;
  ServerCore core_;
  Session* session_ = nullptr;
};

TEST_F(SessionAccessTest, ReadOnlySessionsMayNotWrite) {
  session_->access = UserAccess::Read;
  EXPECT_EQ(writeCount(), 0x801F0000u);  // BadUserAccessDenied
  EXPECT_EQ(core_.pendingWrites().size(), 0u);
  EXPECT_EQ(readByteAttribute(18), 0x01) << "UserAccessLevel: CurrentRead only";
  EXPECT_EQ(readByteAttribute(17), 0x03) << "AccessLevel: what the variable allows";
}

TEST_F(SessionAccessTest, ReadWriteSessionsWrite) {
  session_->access = UserAccess::Write;
  EXPECT_EQ(writeCount(), 0u);
  EXPECT_EQ(core_.pendingWrites().size(), 1u);
  EXPECT_EQ(readByteAttribute(18), 0x03);
}

}  // namespace
}  // namespace virtcom::proto::opcua
