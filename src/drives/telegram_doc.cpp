#include "drives/telegram_doc.hpp"

#include <sstream>
#include <vector>

#include "drives/drive_messages.hpp"
#include "drives/telegram.hpp"

namespace virtcom::drives {
namespace {

// Table cells: a '|' in a meaning (|n_act|) would end the cell.
std::string cell(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

std::string bitRange(const BitDef& b) {
  if (b.width == 1) return std::to_string(b.lsb);
  return std::to_string(b.lsb) + "-" + std::to_string(b.lsb + b.width - 1);
}

void renderLayout(std::ostringstream& out, Layout l) {
  const LayoutDef& def = layout(l);
  out << "\n#### " << def.word << " — " << def.doc << "\n\n| bit | name | meaning when 1 / coding |\n| --- | --- | --- |\n";
  for (const BitDef& b : bits(l)) out << "| " << bitRange(b) << " | " << b.name << " | " << cell(b.doc) << " |\n";
}

void renderTelegram(std::ostringstream& out, const TelegramDef& t) {
  out << "\n## " << t.title << "\n\n"
      << "Key `" << t.key << "`, " << (t.order == ByteOrder::Big ? "big-endian (PROFINET)" : "little-endian (EtherNet/IP)")
      << ", " << t.toDriveBytes << " bytes to the drive, " << t.fromDriveBytes << " bytes from the drive; " << t.source << ".\n\n"
      << "| direction | byte offset | word | type | unit | meaning |\n| --- | --- | --- | --- | --- | --- |\n";
  std::vector<Layout> layoutsUsed;
  for (Dir d : {Dir::ToDrive, Dir::FromDrive})
    for (const WordDef& w : words(t.id, d)) {
      out << "| " << (d == Dir::ToDrive ? "to drive" : "from drive") << " | " << w.offset << " | " << w.name << " | "
          << wireTypeName(w.type) << " | " << unit(w.unit).name << " | " << cell(w.doc) << " |\n";
      if (w.layout != Layout::None) layoutsUsed.push_back(w.layout);
    }
  for (Layout l : layoutsUsed) renderLayout(out, l);
}

}  // namespace

std::string renderTelegramDoc() {
  std::ostringstream out;
  out << "# Drive telegrams\n\n"
      << "<!-- Generated from src/drives/telegrams.def, word_layouts.def, units.def and drive_messages.def by\n"
      << "     `virtcom_drives_doc > docs/drives.md`; do not edit by hand (a unit test compares). -->\n\n"
      << "The process-data images the drive simulators exchange with the PLC (docs/drive-simulators.md shows how\n"
      << "to use them in a cell). Each word is one port of the drive device; a PLC STRUCT whose members carry the\n"
      << "word names wires to all of them at once. Bit 0 is the least significant bit of the logical word (the S7\n"
      << "alias `byte.bit` of a big-endian word is byte 1 - n div 8, bit n mod 8). 32-bit values on PROFINET are\n"
      << "sent high word first, i.e. plain big endian; EtherNet/IP assemblies are little endian.\n\n"
      << "**The reference speed.** N2 and N4 words are fractions of the drive's reference speed p2000, which\n"
      << "both ends must agree on: the drive takes it from its `p2000:` key in the cell file (default 1350 rpm,\n"
      << "docs/drive-simulators.md); the PLC side from the mapping file, `block_inputs: Cfg_RefSpeed` (how\n"
      << "UNIVERSAL_AXIS turns NIST into rpm) and `params: ref_speed` (the named scales `rpm_to_n2`, ...;\n"
      << "docs/universal-axis.md). The bundled mappings in lib/mappings/ say 1350 rpm. When a mapping's value\n"
      << "differs from the drive's p2000 the cell loads with warning C012 at the mapping's value, since the PLC\n"
      << "would read every speed scaled by p2000 / reference.\n\n"
      << "## Units\n\n| unit | definition |\n| --- | --- |\n";
  for (const UnitDef& u : units()) out << "| " << u.name << " | " << cell(u.doc) << " |\n";
  for (const TelegramDef& t : telegrams()) renderTelegram(out, t);
  out << "\n## SINAMICS faults and alarms\n\nThe numbers the Siemens simulators raise and accept for injection"
      << " (`faults: inject:`), with the default fault reaction.\n\n| code | reaction | meaning |\n| --- | --- | --- |\n";
  static const char* kReactions[] = {"-", "OFF1", "OFF2", "OFF3"};
  for (const MessageDef& m : messageCatalogue())
    out << "| " << messageName(m.kind, m.number) << " | " << kReactions[static_cast<int>(m.reaction)] << " | " << cell(m.meaning) << " |\n";
  out << "\n## PowerFlex faults\n\nThe fault numbers of the PowerFlex simulators (Fault 1 Code; `faults: inject:` takes"
      << " `F7` or `7`). Every fault coasts the motor.\n\n| fault | meaning |\n| --- | --- |\n";
  for (const PowerFlexFaultDef& f : powerFlexFaults()) out << "| F" << f.number << " | " << cell(f.meaning) << " |\n";
  return out.str();
}

}  // namespace virtcom::drives
