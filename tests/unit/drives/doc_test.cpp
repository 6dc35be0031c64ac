// docs/drives.md is generated from the telegram tables; the committed file must match.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "drives/telegram_doc.hpp"

namespace virtcom::drives {
namespace {

TEST(DrivesDoc, CommittedFileMatchesTheTables) {
  std::ifstream in(std::string(VIRTCOM_SOURCE_DIR) + "/docs/drives.md");
  ASSERT_TRUE(in) << "docs/drives.md is missing";
  std::stringstream committed;
  committed << in.rdbuf();
  // Only the first differing line is shown: the whole document would drown the message.
  std::istringstream want(renderTelegramDoc()), have(committed.str());
  std::string wantLine, haveLine;
  for (int line = 1; std::getline(want, wantLine); ++line) {
    if (!std::getline(have, haveLine)) haveLine = "<end of file>";
    ASSERT_EQ(haveLine, wantLine) << "docs/drives.md:" << line
                                  << " is out of date: regenerate with `virtcom_drives_doc > docs/drives.md`";
  }
  EXPECT_FALSE(std::getline(have, haveLine)) << "docs/drives.md has extra lines";
}

TEST(DrivesDoc, ListsEveryTelegramWordAndBit) {
  const std::string doc = renderTelegramDoc();
  for (const char* needle : {"siemens_std1", "siemens_352", "siemens_std111", "ab_pf525_velocity", "ab_pf750",
                             "| to drive | 10 | MDI_TARPOS | i32 | LU |", "| 4-5 | Direction |", "| 12-15 | MasterSignOfLife |",
                             "| F01910 | OFF3 |"})
    EXPECT_NE(doc.find(needle), std::string::npos) << needle;
}

}  // namespace
}  // namespace virtcom::drives
