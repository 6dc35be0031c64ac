// Golden bytes for every built-in type of builtin_types.def (OPC 10000-6 §5.2.2), each checked
// both ways: encoded to exactly the bytes, and those bytes decoded back to the value.
#include "proto/opcua/binary_codec.hpp"

#include <gtest/gtest.h>

#include <string>

#include "hex_bytes.hpp"

namespace virtcom::proto::opcua {
namespace {

using testing::hex;
using testing::unhex;

// The value encodes to `golden`, and `golden` decodes (wholly) back to the value.
template <class T>
void expectGolden(const T& value, const std::string& golden) {
  std::vector<uint8_t> out;
  Writer w(out);
  encode(w, value);
  EXPECT_EQ(hex(out), golden);
  auto bytes = unhex(golden);
  Reader r(bytes);
  T back{};
  ASSERT_TRUE(decode(r, back)) << golden;
  EXPECT_EQ(r.remaining(), 0u) << golden;
  EXPECT_TRUE(back == value) << golden;
}

template <class T>
bool decodes(std::string_view golden) {
  auto bytes = unhex(golden);
  Reader r(bytes);
  T back{};
  return decode(r, back);
}

TEST(OpcuaBinaryCodec, FixedSizeNumbers) {
  expectGolden(true, "01");
  expectGolden(int8_t{-2}, "FE");
  expectGolden(uint8_t{200}, "C8");
  expectGolden(int16_t{-2}, "FE FF");
  expectGolden(uint16_t{0x1234}, "34 12");
  expectGolden(int32_t{-2}, "FE FF FF FF");
  expectGolden(uint32_t{0x12345678}, "78 56 34 12");
  expectGolden(int64_t{-2}, "FE FF FF FF FF FF FF FF");
  expectGolden(uint64_t{0x0102030405060708}, "08 07 06 05 04 03 02 01");
  expectGolden(1.0f, "00 00 80 3F");
  expectGolden(1.0, "00 00 00 00 00 00 F0 3F");
  expectGolden(DateTime{0x01D0000000000001}, "01 00 00 00 00 00 D0 01");
  expectGolden(StatusCode{0x80340000}, "00 00 34 80");
}

TEST(OpcuaBinaryCodec, StringsAndBytes) {
  expectGolden(String{"abc", false}, "03 00 00 00 61 62 63");
  expectGolden(String{"", true}, "FF FF FF FF");
  expectGolden(String{"", false}, "00 00 00 00");
  expectGolden(ByteString{"\xDE\xAD", false}, "02 00 00 00 DE AD");
  expectGolden(ByteString{"", true}, "FF FF FF FF");
  expectGolden(XmlElement{"<a/>"}, "04 00 00 00 3C 61 2F 3E");
  EXPECT_FALSE(decodes<String>("05 00 00 00 61"));  // shorter than its length
  EXPECT_FALSE(decodes<String>("FE FF FF FF"));     // -2 is no length
}

TEST(OpcuaBinaryCodec, GuidAsPartSixExample) {
  // {72962B91-FA75-4AE6-8D28-B404DC7DAF63}: OPC 10000-6 §5.2.2.7 (Data1..3 little endian).
  Guid g{0x72962B91, 0xFA75, 0x4AE6, {0x8D, 0x28, 0xB4, 0x04, 0xDC, 0x7D, 0xAF, 0x63}};
  expectGolden(g, "91 2B 96 72 75 FA E6 4A 8D 28 B4 04 DC 7D AF 63");
}

TEST(OpcuaBinaryCodec, NodeIdPicksTheShortestEncoding) {
  expectGolden(NodeId::num(0, 85), "00 55");                               // two-byte
  expectGolden(NodeId::num(5, 1025), "01 05 01 04");                       // four-byte
  expectGolden(NodeId::num(1, 0x10000), "02 01 00 00 00 01 00");           // numeric
  expectGolden(NodeId::num(300, 1), "02 2C 01 01 00 00 00");               // ns > 255
  expectGolden(NodeId::str(4, "ab"), "03 04 00 02 00 00 00 61 62");        // string
  NodeId guid{1, NodeId::Kind::Guid, 0, {}, Guid{1, 2, 3, {4, 5, 6, 7, 8, 9, 10, 11}}};
  expectGolden(guid, "04 01 00 01 00 00 00 02 00 03 00 04 05 06 07 08 09 0A 0B");
  expectGolden(NodeId{2, NodeId::Kind::Opaque, 0, "\x01\x02", {}}, "05 02 00 02 00 00 00 01 02");
  EXPECT_FALSE(decodes<NodeId>("06 00 00"));  // no such encoding
  EXPECT_FALSE(decodes<NodeId>("80 55"));     // ExpandedNodeId flags on a NodeId
  EXPECT_FALSE(decodes<NodeId>("01 05 01"));  // truncated
}

TEST(OpcuaBinaryCodec, ExpandedNodeIdFlags) {
  expectGolden(ExpandedNodeId{NodeId::num(0, 85), "", 0}, "00 55");
  expectGolden(ExpandedNodeId{NodeId::num(0, 85), "u", 2}, "C0 55 01 00 00 00 75 02 00 00 00");
  expectGolden(ExpandedNodeId{NodeId::str(1, "x"), "", 3}, "43 01 00 01 00 00 00 78 03 00 00 00");
}

TEST(OpcuaBinaryCodec, NamesAndTexts) {
  expectGolden(QualifiedName{1, "x"}, "01 00 01 00 00 00 78");
  expectGolden(LocalizedText{"en", "hi"}, "03 02 00 00 00 65 6E 02 00 00 00 68 69");
  expectGolden(LocalizedText{"", "hi"}, "02 02 00 00 00 68 69");
  expectGolden(LocalizedText{}, "00");
}

TEST(OpcuaBinaryCodec, ExtensionObjectBodies) {
  expectGolden(ExtensionObject{NodeId::num(0, 321), ExtensionObject::Body::Binary, "\x01"}, "01 00 41 01 01 01 00 00 00 01");
  expectGolden(ExtensionObject{}, "00 00 00");
  expectGolden(ExtensionObject{NodeId::num(0, 1), ExtensionObject::Body::Xml, "<a/>"}, "00 01 02 04 00 00 00 3C 61 2F 3E");
  EXPECT_FALSE(decodes<ExtensionObject>("00 00 03"));  // body encoding 3 does not exist
}

TEST(OpcuaBinaryCodec, VariantScalarsArraysAndDimensions) {
  expectGolden(Variant{}, "00");
  expectGolden(Variant::scalar(int32_t{5}), "06 05 00 00 00");
  expectGolden(Variant::scalar(String{"a", false}), "0C 01 00 00 00 61");
  Variant array{BuiltinType::Int16, true, {int16_t{1}, int16_t{2}}, {}};
  expectGolden(array, "84 02 00 00 00 01 00 02 00");
  Variant matrix{BuiltinType::Int32, true, {int32_t{1}, int32_t{2}}, {2, 1}};
  expectGolden(matrix, "C6 02 00 00 00 01 00 00 00 02 00 00 00 02 00 00 00 02 00 00 00 01 00 00 00");
  Variant empty{BuiltinType::Boolean, true, {}, {}};
  expectGolden(empty, "81 00 00 00 00");
  EXPECT_FALSE(decodes<Variant>("1A"));                    // type id 26 is not a built-in
  EXPECT_FALSE(decodes<Variant>("86 FF FF FF 7F"));        // 2^31 elements in 0 bytes
  EXPECT_TRUE(decodes<Variant>("86 FF FF FF FF"));         // a null array
}

TEST(OpcuaBinaryCodec, NestedVariantsAndDataValuesAreCut) {
  // A Variant of Variant of ... (type 24): allowed to kMaxNesting levels, refused beyond.
  std::string deep;
  for (int i = 0; i < kMaxNesting + 1; ++i) deep += "18 ";
  deep += "00";
  EXPECT_FALSE(decodes<Variant>(deep));
  EXPECT_TRUE(decodes<Variant>("18 18 06 05 00 00 00"));
}

TEST(OpcuaBinaryCodec, DataValueMaskFields) {
  DataValue v;
  v.hasValue = v.hasStatus = true;
  v.value = Variant::scalar(int32_t{5});
  v.status = 0x80340000;
  expectGolden(v, "03 06 05 00 00 00 00 00 34 80");
  DataValue t;
  t.hasSourceTime = t.hasServerTime = true;
  t.sourceTime = DateTime{1};
  t.sourcePicoseconds = 10;
  t.serverTime = DateTime{2};
  expectGolden(t, "1C 01 00 00 00 00 00 00 00 0A 00 02 00 00 00 00 00 00 00");
  expectGolden(DataValueBox{std::make_shared<DataValue>(v)}, "03 06 05 00 00 00 00 00 34 80");
}

TEST(OpcuaBinaryCodec, DiagnosticInfoMaskFields) {
  DiagnosticInfo d;
  d.symbolicId = 1;
  d.locale = 2;
  d.hasInnerStatus = true;
  d.innerStatus = 0x80020000;
  d.inner = std::make_shared<DiagnosticInfo>();
  d.inner->hasAdditionalInfo = true;
  d.inner->additionalInfo = "x";
  expectGolden(d, "69 01 00 00 00 02 00 00 00 00 00 02 80 10 01 00 00 00 78");
  expectGolden(DiagnosticInfo{}, "00");
}

TEST(OpcuaBinaryCodec, EveryBuiltinTypeRoundTripsThroughAVariant) {
  // The table's dispatch: a scalar of each type id decodes to that type.
  for (int id = 1; id <= 25; ++id) {
    Scalar s;
    std::vector<uint8_t> zero(64, 0);
    Reader r(zero);
    ASSERT_TRUE(decodeScalar(r, static_cast<BuiltinType>(id), s)) << id;
    EXPECT_EQ(static_cast<int>(s.index()), id);
    Variant v = Variant::scalar(s);
    std::vector<uint8_t> out;
    Writer w(out);
    encode(w, v);
    Reader back(out);
    Variant got;
    ASSERT_TRUE(decode(back, got)) << builtinTypeName(static_cast<BuiltinType>(id));
    EXPECT_TRUE(got == v) << builtinTypeName(static_cast<BuiltinType>(id));
  }
}

TEST(OpcuaBinaryCodec, NodeIdText) {
  EXPECT_EQ(formatNodeId(NodeId::num(0, 85)), "i=85");
  EXPECT_EQ(formatNodeId(NodeId::str(4, "|var|virtcom.Application.MAIN.x")), "ns=4;s=|var|virtcom.Application.MAIN.x");
  EXPECT_EQ(statusName(0x80340000), "BadNodeIdUnknown");
  EXPECT_EQ(statusName(0x8abc0000), "0x8abc0000");
}

}  // namespace
}  // namespace virtcom::proto::opcua
