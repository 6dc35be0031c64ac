#include "plc/write_audit.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <numeric>

#include "core/clock.hpp"

namespace virtcom::plc {

namespace {

uint32_t sizeOf(const bc::Module& m, const bc::VarRef& r) {
  if (r.bit >= 0) return 1;
  return r.type < m.types.size() ? m.types[r.type].size : 0;
}

// Narrows `ref` (named `name`) to the struct member or array element that holds all of
// [lo, hi), as deep as one does: "MAIN.s" -> "MAIN.s.a[2]".
void narrow(const bc::Module& m, std::string& name, bc::VarRef& ref, uint32_t lo, uint32_t hi) {
  while (ref.bit < 0 && ref.type < m.types.size()) {
    const bc::TypeDesc& t = m.types[ref.type];
    if (t.kind == bc::TypeKind::Struct) {
      auto f = std::find_if(t.fields.begin(), t.fields.end(), [&](const bc::Field& f) {
        if (f.absolute || f.bit >= 0 || f.type >= m.types.size()) return false;
        const uint32_t at = ref.address + f.offset;
        return lo >= at && hi <= at + m.types[f.type].size;
      });
      if (f == t.fields.end()) return;
      name += "." + f->name;
      ref = {f->type, ref.address + f->offset, -1, ref.readOnly};
    } else if (t.kind == bc::TypeKind::Array && t.dims.size() == 1 && t.element < m.types.size()) {
      const uint32_t each = m.types[t.element].size;
      if (each == 0) return;
      const uint32_t index = (lo - ref.address) / each;
      const uint32_t at = ref.address + index * each;
      if (index >= t.dims[0].count() || hi > at + each) return;
      name += "[" + std::to_string(t.dims[0].lo + static_cast<int64_t>(index)) + "]";
      ref = {t.element, at, -1, ref.readOnly};
    } else {
      return;
    }
  }
}

// "%QX0.3", "%MW4", "%IB2"...: the IEC address of a variable in a process area, else "".
std::string locationOf(const bc::Module& m, const bc::VarRef& r, uint32_t size) {
  struct Area {
    const bc::ProcessArea& area;
    char letter;
  };
  for (const Area& a : {Area{m.inputs, 'I'}, Area{m.outputs, 'Q'}, Area{m.memory, 'M'}}) {
    if (r.address < a.area.address || r.address - a.area.address >= a.area.size) continue;
    const uint32_t byte = r.address - a.area.address;
    if (r.bit >= 0) return "%" + std::string(1, a.letter) + "X" + std::to_string(byte) + "." + std::to_string(r.bit);
    const char width = size == 1 ? 'B' : size == 2 ? 'W' : size == 4 ? 'D' : 'L';
    return "%" + std::string(1, a.letter) + width + std::to_string(size == 1 ? byte : byte / size);
  }
  return "";
}

std::string hexBytes(std::span<const uint8_t> bytes) {
  std::string out = "16#";
  char two[3];
  for (uint8_t b : bytes) {
    std::snprintf(two, sizeof two, "%02X", b);
    out += two;
  }
  return out;
}

}  // namespace

std::string formatWriteRecord(const WriteRecord& r) {
  return std::string(writeProtocolName(r.writer.protocol)) + " " + writerPeer(r.writer) + " " + writtenVariableText(r) + ": " + r.oldValue + " -> " + r.newValue + (r.writer.force ? " (forced)" : "");
}

std::string formatWriteRecordWithTimes(const WriteRecord& r) {
  char virtualTime[32];
  std::snprintf(virtualTime, sizeof virtualTime, "%.3fs", static_cast<double>(r.virtualNs) * 1e-9);
  return std::string(virtualTime) + " " + utcTimeText(r.wallNs) + " " + formatWriteRecord(r);
}

WriteAudit::WriteAudit(const bc::Module& module, Sink sink) : m_(module), sink_(std::move(sink)), shadow_(module.staticSize) {
  for (bc::NamedVar& v : bc::listVariables(module)) {
    const uint32_t size = sizeOf(module, v.ref);
    if (size > 0) vars_.push_back({std::move(v.name), v.ref, size});
  }
  std::stable_sort(vars_.begin(), vars_.end(), [](const Variable& a, const Variable& b) { return a.ref.address < b.ref.address; });
}

uint64_t WriteAudit::total() const { return std::accumulate(counts_.begin(), counts_.end(), uint64_t{0}); }

void WriteAudit::beforeEdit(const ExternalWriter& writer, std::span<const uint8_t> target, uint32_t address, uint32_t offset,
                            uint32_t size, uint8_t bitMask) {
  if (offset >= target.size() || size == 0) return;
  size = std::min<uint32_t>(size, static_cast<uint32_t>(target.size() - offset));
  const uint32_t lo = address + offset, hi = lo + size;
  const int bit = bitMask ? std::countr_zero(bitMask) : -1;
  // The declared variables the edit touches, each wholly inside `target`.
  auto touched = [&](const Variable& v) {
    if (v.ref.address < address || v.ref.address + v.size > address + target.size()) return false;
    if (v.ref.bit >= 0) return v.ref.address >= lo && v.ref.address < hi && (bitMask == 0 || v.ref.bit == bit);
    return v.ref.address < hi && v.ref.address + v.size > lo;
  };
  // A bit write names the BOOL at that bit when one is declared, not the WORD around it too.
  const bool bitDeclared = bitMask && std::any_of(vars_.begin(), vars_.end(), [&](const Variable& v) { return v.ref.bit >= 0 && touched(v); });
  auto wanted = [&](const Variable& v) { return touched(v) && (!bitDeclared || v.ref.bit >= 0); };
  candidates_.clear();
  for (const Variable& v : vars_) {
    if (!wanted(v)) continue;
    Pending c{writer, v.name, v.ref, v.size, nullptr, 0, 0};
    if (c.ref.bit < 0) narrow(m_, c.name, c.ref, std::max(lo, v.ref.address), std::min(hi, v.ref.address + v.size));
    c.size = sizeOf(m_, c.ref);
    candidates_.push_back(std::move(c));
  }
  // Nothing declared there: the bytes themselves, by location.
  if (candidates_.empty()) candidates_.push_back({writer, {}, bc::VarRef{bc::kNoType, lo, static_cast<int8_t>(bit), false}, size, nullptr, 0, 0});
  for (Pending& c : candidates_) c.at = target.data() + (c.ref.address - address);
  // Consecutive edits of the same variables by the same writer (the bytes of one register, the
  // bits of one request) are one write: its old value was taken at the first edit.
  auto same = [](const Pending& a, const Pending& b) {
    return a.writer == b.writer && a.ref.address == b.ref.address && a.ref.bit == b.ref.bit && a.size == b.size && a.name == b.name;
  };
  if (std::equal(pending_.begin() + static_cast<ptrdiff_t>(openFrom_), pending_.end(), candidates_.begin(), candidates_.end(), same)) return;
  closeOpen();
  for (Pending& c : candidates_) {
    c.oldPos = bytes_.size();
    bytes_.insert(bytes_.end(), c.at, c.at + c.size);
    pending_.push_back(std::move(c));
  }
}

void WriteAudit::closeOpen() {
  for (size_t i = openFrom_; i < pending_.size(); ++i) {
    Pending& p = pending_[i];
    p.newPos = bytes_.size();
    bytes_.insert(bytes_.end(), p.at, p.at + p.size);
  }
  openFrom_ = pending_.size();
}

WriteRecord WriteAudit::toRecord(const Pending& p, int64_t wallNs) {
  WriteRecord r;
  r.virtualNs = virtualNs_;
  r.wallNs = wallNs;
  r.writer = p.writer;
  auto value = [&](size_t pos) {
    const auto bytes = std::span<const uint8_t>(bytes_).subspan(pos, p.size);
    if (p.name.empty() || p.ref.type >= m_.types.size() || p.ref.address + p.size > shadow_.size()) {
      if (p.ref.bit >= 0) return std::string((bytes[0] >> p.ref.bit) & 1 ? "TRUE" : "FALSE");
      return hexBytes(bytes);
    }
    std::copy(bytes.begin(), bytes.end(), shadow_.begin() + p.ref.address);
    return bc::formatValue(m_, p.ref, shadow_.data());
  };
  r.location = locationOf(m_, p.ref, p.size);
  r.variable = !p.name.empty() ? p.name : !r.location.empty() ? r.location : "address " + std::to_string(p.ref.address);
  r.oldValue = value(p.oldPos);
  r.newValue = value(p.newPos);
  return r;
}

void WriteAudit::endEdits() {
  if (pending_.empty()) return;
  closeOpen();
  const int64_t wallNs = utcNowNs();
  for (const Pending& p : pending_) {
    ++counts_[static_cast<size_t>(p.writer.protocol)];
    if (sink_) sink_(toRecord(p, wallNs));
  }
  pending_.clear();
  bytes_.clear();
  openFrom_ = 0;
}

void WriteAudit::stateChanged(const ExternalWriter& writer, std::string_view from, std::string_view to) {
  ++counts_[static_cast<size_t>(writer.protocol)];
  if (!sink_) return;
  WriteRecord r;
  r.virtualNs = virtualNs_;
  r.wallNs = utcNowNs();
  r.writer = writer;
  r.variable = kPlcStateVariable;
  r.oldValue = from;
  r.newValue = to;
  sink_(r);
}

}  // namespace virtcom::plc
