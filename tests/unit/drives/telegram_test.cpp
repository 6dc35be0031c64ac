// Telegram tables and codec: wire bytes, bits, normalisation (docs/drives.md).
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "drives/normalisation.hpp"
#include "drives/telegram.hpp"

namespace virtcom::drives {
namespace {

std::vector<uint8_t> encodeAll(TelegramId t, Dir d, std::vector<uint32_t> raw) {
  std::vector<uint8_t> image(imageBytes(t, d), 0xAA);
  EXPECT_TRUE(encode(t, d, raw, image));
  return image;
}

TEST(Telegram, Std1ControlWordsAreBigEndianOnTheWire) {  // E31
  auto image = encodeAll(TelegramId::Std1, Dir::ToDrive, {0x047F, rawFromInt(WireType::I16, 8192)});
  EXPECT_EQ(image, (std::vector<uint8_t>{0x04, 0x7F, 0x20, 0x00}));
  std::array<uint32_t, 2> back{};
  ASSERT_TRUE(decode(TelegramId::Std1, Dir::ToDrive, image, back));
  EXPECT_EQ(back[0], 0x047Fu);
  EXPECT_EQ(signedValue(WireType::I16, back[1]), 8192);
}

TEST(Telegram, Pf525IsLittleEndianOnTheWire) {  // E31
  auto image = encodeAll(TelegramId::Pf525, Dir::ToDrive, {0x0012, 1188});
  EXPECT_EQ(image, (std::vector<uint8_t>{0x12, 0x00, 0xA4, 0x04}));
  std::array<uint32_t, 2> back{};
  ASSERT_TRUE(decode(TelegramId::Pf525, Dir::ToDrive, image, back));
  EXPECT_EQ(back[0], 0x0012u);
  EXPECT_EQ(back[1], 1188u);
  // jog 475 = 0x01DB (E20)
  EXPECT_EQ(encodeAll(TelegramId::Pf525, Dir::ToDrive, {0x0012, 475})[2], 0xDB);
}

TEST(Telegram, Std111PositionsAreBigEndian32Bit) {  // E13, E14
  RawWords raw{};
  raw[wordSlot(TelegramId::Std111, Dir::ToDrive, "MDI_TARPOS").index] = rawFromInt(WireType::I32, 70000);
  std::array<uint8_t, 24> image{};
  ASSERT_TRUE(encode(TelegramId::Std111, Dir::ToDrive, raw, image));
  EXPECT_EQ((std::array<uint8_t, 4>{image[10], image[11], image[12], image[13]}), (std::array<uint8_t, 4>{0x00, 0x01, 0x11, 0x70}));
  writeWire(image, 10, WireType::I32, ByteOrder::Big, rawFromInt(WireType::I32, -123456));
  EXPECT_EQ(signedValue(WireType::I32, readWire(image, 10, WireType::I32, ByteOrder::Big)), -123456);
}

TEST(Telegram, Pf750ReferenceIsALittleEndianReal) {
  std::vector<uint8_t> image(8, 0);
  ASSERT_TRUE(encode(TelegramId::Pf750, Dir::ToDrive, std::vector<uint32_t>{0x12, rawFromReal(30.0)}, image));
  EXPECT_EQ(image[0], 0x12);
  EXPECT_EQ((std::array<uint8_t, 4>{image[4], image[5], image[6], image[7]}), (std::array<uint8_t, 4>{0x00, 0x00, 0xF0, 0x41}));
  std::array<uint32_t, 2> back{};
  ASSERT_TRUE(decode(TelegramId::Pf750, Dir::ToDrive, image, back));
  EXPECT_DOUBLE_EQ(realValue(back[1]), 30.0);
}

TEST(Telegram, ShortImagesAreRefused) {
  std::array<uint8_t, 3> shortImage{};
  std::array<uint32_t, 2> raw{};
  EXPECT_FALSE(decode(TelegramId::Std1, Dir::FromDrive, shortImage, raw));
  EXPECT_FALSE(encode(TelegramId::Std1, Dir::FromDrive, raw, shortImage));
}

TEST(Telegram, LookupsFindWordsBitsAndTelegrams) {
  EXPECT_EQ(findTelegram("siemens_352"), TelegramId::Siemens352);
  EXPECT_FALSE(findTelegram("siemens_2").has_value());
  EXPECT_EQ(words(TelegramId::Siemens352, Dir::FromDrive).size(), 6u);
  EXPECT_EQ(words(TelegramId::Std111, Dir::ToDrive).size(), 10u);
  EXPECT_FALSE(findWord(TelegramId::Std1, Dir::ToDrive, "ZSW1").has_value());
  const BitDef* dir = findBit(Layout::Pf525Command, "Direction");
  ASSERT_NE(dir, nullptr);
  EXPECT_EQ(dir->mask(), 0x0030u);
  EXPECT_EQ(findBit(Layout::Pf525Command, "Nope"), nullptr);
  // STW1 0.2 in S7 notation = bit 10 = control by PLC
  EXPECT_EQ(bitDef(Layout::Stw1Speed, "ControlByPlc").lsb, 10);
  EXPECT_EQ(bitDef(Layout::Stw2, "MasterSignOfLife").mask(), 0xF000u);
}

TEST(Telegram, FieldsReadAndWriteMultiBitCodes) {
  const BitDef freqSel = bitDef(Layout::Pf525Command, "FreqSelect");
  uint32_t w = withField(0x0012, freqSel, 0b101);
  EXPECT_EQ(w, 0x5012u);
  EXPECT_EQ(field(w, freqSel), 5u);
  EXPECT_EQ(field(0x0022, bitDef(Layout::Pf525Command, "Direction")), 0b10u);
  EXPECT_TRUE(test(0x047F, bitDef(Layout::Stw1Speed, "On")));
  EXPECT_FALSE(test(0x047E, bitDef(Layout::Stw1Speed, "On")));
  EXPECT_EQ(withBit(0x047E, bitDef(Layout::Stw1Speed, "AckFault"), true), 0x04FEu);
}

TEST(Normalisation, ThesisFigures) {
  EXPECT_EQ(n2FromRpm(675, 1350), 8192);             // E1: 50 % of p2000 = 0x2000
  EXPECT_DOUBLE_EQ(rpmFromN2(8192, 1350), 675.0);
  EXPECT_EQ(n2FromRpm(1012.5, 1350), 12288);         // E2: 75 %
  EXPECT_EQ(q14FromPercent(80), 13107);              // E6: 0x3333
  EXPECT_NEAR(rpmFromN2(13107, 1350), 1079.98, 0.01);
  EXPECT_EQ(q14FromPercent(20), 3277);               // E4: 0x0CCD
  EXPECT_NEAR(rpmFromN2(3277, 1350), 270.02, 0.01);
  EXPECT_EQ(centiHzFromRpm(600, 1), 1000);           // 600 rpm = 10.00 Hz
  EXPECT_EQ(centiHzFromRpm(712.5, 1), 1188);         // E18: 1187.5 -> 1188
  EXPECT_NEAR(rpmFromCentiHz(1188, 1), 712.8, 1e-9);
  EXPECT_EQ(centiHzFromRpm(285, 1), 475);            // E20
  EXPECT_EQ(n4FromRpm(1350, 1350), 0x40000000);
  EXPECT_DOUBLE_EQ(rpmFromN4(0x20000000, 1350), 675.0);
}

TEST(Normalisation, RoundsHalfToEvenAndSaturates) {
  EXPECT_EQ(roundSaturate(2.5, -10, 10), 2);
  EXPECT_EQ(roundSaturate(3.5, -10, 10), 4);
  EXPECT_EQ(roundSaturate(-2.5, -10, 10), -2);
  EXPECT_EQ(n2FromRpm(5000, 1350), 32767);           // +199.99 % limit
  EXPECT_EQ(n2FromRpm(-5000, 1350), -32768);
  EXPECT_EQ(n2FromRpm(-675, 1350), -8192);           // 0xE000
  EXPECT_EQ(rawFromInt(WireType::I16, -8192), 0xE000u);
}

}  // namespace
}  // namespace virtcom::drives
