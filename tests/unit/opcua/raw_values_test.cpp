// Golden bytes of what the client bridge writes into its Read and Write requests, and its
// reading of a Read response's DataValues as the bytes of their scalars.
#include "proto/opcua/raw_values.hpp"

#include <gtest/gtest.h>

#include "hex_bytes.hpp"
#include "proto/opcua/services.hpp"

namespace virtcom::proto::opcua {
namespace {

using testing::hex;
using testing::unhex;

std::vector<uint8_t> encodedNode() {
  std::vector<uint8_t> out;
  Writer w(out);
  encode(w, NodeId::str(4, "x"));
  return out;
}

// Regression: the bridge sent the DataEncoding as an empty name ("00 00 00 00 00 00"), which
// node-opcua takes for an encoding asked for and answers the UserAccessLevel of every node with
// BadDataEncodingInvalid: the bridge found no device output writable.
TEST(OpcuaRawValues, AReadValueIdHasANullIndexRangeAndANullDataEncoding) {
  std::vector<uint8_t> out;
  Writer w(out);
  encodeReadValueId(w, encodedNode(), kUserAccessLevelAttr);
  EXPECT_EQ(hex(out), "03 04 00 01 00 00 00 78 12 00 00 00 FF FF FF FF 00 00 FF FF FF FF");
}

TEST(OpcuaRawValues, AWriteValueCarriesTheValueAsAScalarVariantAlone) {
  std::vector<uint8_t> out;
  Writer w(out);
  const uint8_t value[] = {0x34, 0x12};
  encodeWriteValue(w, encodedNode(), BuiltinType::Int16, value);
  EXPECT_EQ(hex(out), "03 04 00 01 00 00 00 78 0D 00 00 00 FF FF FF FF 01 04 34 12");
}

TEST(OpcuaRawValues, AScalarsBytesAreReadPastEveryOptionalField) {
  // Value Int16 0x1234, a Good status, both timestamps with their picoseconds, then a Boolean.
  auto bytes = unhex("3F 04 34 12 00 00 00 00 01 02 03 04 05 06 07 08 09 00 01 02 03 04 05 06 07 08 0A 00 01 01 01");
  Reader r(bytes);
  RawValue v;
  ASSERT_TRUE(readRawValue(r, v));
  EXPECT_EQ(v.type, BuiltinType::Int16);
  EXPECT_EQ(hex({v.bytes.begin(), v.bytes.end()}), "34 12");
  EXPECT_EQ(v.status, 0u);
  ASSERT_TRUE(readRawValue(r, v));
  EXPECT_EQ(v.type, BuiltinType::Boolean);
  EXPECT_EQ(hex({v.bytes.begin(), v.bytes.end()}), "01");
  EXPECT_EQ(r.remaining(), 0u);
}

TEST(OpcuaRawValues, AStatusAloneIsABadValueWithoutType) {
  auto bytes = unhex("02 00 00 34 80");
  Reader r(bytes);
  RawValue v;
  ASSERT_TRUE(readRawValue(r, v));
  EXPECT_EQ(v.status, static_cast<uint32_t>(StatusCodeValue::BadNodeIdUnknown));
  EXPECT_EQ(v.type, BuiltinType::Null);
  EXPECT_TRUE(v.bytes.empty());
}

TEST(OpcuaRawValues, ArraysAndStringsAreTypedButNotRead) {
  auto array = unhex("01 84 02 00 00 00 01 00 02 00");
  Reader a(array);
  RawValue v;
  ASSERT_TRUE(readRawValue(a, v));
  EXPECT_TRUE(v.isArray);
  EXPECT_EQ(v.type, BuiltinType::Int16);
  EXPECT_TRUE(v.bytes.empty());
  auto text = unhex("01 0C 01 00 00 00 61");
  Reader s(text);
  ASSERT_TRUE(readRawValue(s, v));
  EXPECT_EQ(v.type, BuiltinType::String);
  EXPECT_TRUE(v.bytes.empty());
}

TEST(OpcuaRawValues, ATruncatedValueIsMalformed) {
  for (const char* cut : {"", "01", "01 0B 00 00 00 00 00 00 00", "03 01 01 00 00", "05 01 01 00 00 00 00"}) {
    auto bytes = unhex(cut);
    Reader r(bytes);
    RawValue v;
    EXPECT_FALSE(readRawValue(r, v)) << cut;
  }
}

}  // namespace
}  // namespace virtcom::proto::opcua
