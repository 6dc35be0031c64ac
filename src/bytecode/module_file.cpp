#include "bytecode/module_file.hpp"

#include <concepts>
#include <cstring>
#include <iterator>
#include <type_traits>

#include "core/content_hash.hpp"

namespace virtcom::bc {

namespace {

// "VCMODULE" then the format version: a change of Module's members changes the version.
constexpr std::string_view kMagic = "VCMODULE";

// How many members an aggregate has: the most initialisers `T{...}` takes.
struct AnyValue {
  template <class U> operator U() const;
};
template <class T, class... Given>
consteval size_t memberCount() {
  if constexpr (requires { T{Given{}..., AnyValue{}}; })
    return memberCount<T, Given..., AnyValue>();
  else
    return sizeof...(Given);
}

// A member added to a struct of the module stops the build here: add it to `members` below,
// raise kFormatVersion, then the count.
static_assert(memberCount<SourceLocation>() == 3 && memberCount<ArrayDim>() == 2 && memberCount<Enumerator>() == 2);
static_assert(memberCount<Field>() == 9 && memberCount<TypeDesc>() == 10 && memberCount<PouInfo>() == 8);
static_assert(memberCount<IndexDesc>() == 3 && memberCount<LineEntry>() == 2 && memberCount<Symbol>() == 6);
static_assert(memberCount<ProgramInstance>() == 3 && memberCount<TaskInfo>() == 5 && memberCount<ProcessArea>() == 2);
static_assert(memberCount<CoverageProbe>() == 6 && memberCount<CoverageTable>() == 2 && memberCount<Module>() == 22);
constexpr uint32_t kFormatVersion = 1;
constexpr size_t kChecksumBytes = sizeof(uint64_t);

template <class T, class U>
concept Is = std::same_as<std::remove_const_t<T>, U>;

template <class T>
concept Scalar = std::is_arithmetic_v<T> || std::is_enum_v<T>;

// The largest valid value of each enumeration a file holds (a byte beyond it is refused); an
// enumeration added to a module without one here does not compile.
constexpr uint8_t lastValue(TypeKind) { return static_cast<uint8_t>(TypeKind::Reference); }
constexpr uint8_t lastValue(PouKind) { return static_cast<uint8_t>(PouKind::Init); }
constexpr uint8_t lastValue(CoverageKind) { return static_cast<uint8_t>(CoverageKind::Rule); }
constexpr uint8_t lastValue(ElemType) { return static_cast<uint8_t>(std::size(kElemTypeInfo) - 1); }
constexpr uint8_t lastValue(bool) { return 1; }

// The members of every struct of a module, in file order: one list for writing and reading.
template <class Io> void members(Io& io, Is<SourceLocation> auto& l) { io(l.fileId), io(l.line), io(l.col); }
template <class Io> void members(Io& io, Is<ArrayDim> auto& d) { io(d.lo), io(d.hi); }
template <class Io> void members(Io& io, Is<Field> auto& f) {
  io(f.name), io(f.type), io(f.offset), io(f.bit), io(f.hidden), io(f.readOnly), io(f.absolute), io(f.section),
      io(f.retain);
}
template <class Io> void members(Io& io, Is<Enumerator> auto& e) { io(e.name), io(e.value); }
template <class Io> void members(Io& io, Is<TypeDesc> auto& t) {
  io(t.kind), io(t.name), io(t.size), io(t.align), io(t.elem), io(t.element), io(t.dims), io(t.fields),
      io(t.enumerators), io(t.stringLength);
}
template <class Io> void members(Io& io, Is<PouInfo> auto& p) {
  io(p.name), io(p.kind), io(p.codeStart), io(p.codeSize), io(p.numRegs), io(p.frameSize), io(p.frameTemplate),
      io(p.instanceType);
}
template <class Io> void members(Io& io, Is<IndexDesc> auto& i) { io(i.lo), io(i.count), io(i.stride); }
template <class Io> void members(Io& io, Is<LineEntry> auto& l) { io(l.pc), io(l.loc); }
template <class Io> void members(Io& io, Is<Symbol> auto& s) {
  io(s.name), io(s.type), io(s.address), io(s.readOnly), io(s.retain), io(s.bit);
}
template <class Io> void members(Io& io, Is<ProgramInstance> auto& p) { io(p.name), io(p.pou), io(p.address); }
template <class Io> void members(Io& io, Is<TaskInfo> auto& t) {
  io(t.name), io(t.intervalNs), io(t.priority), io(t.programs), io(t.isDefault);
}
template <class Io> void members(Io& io, Is<ProcessArea> auto& a) { io(a.address), io(a.size); }
template <class Io> void members(Io& io, Is<CoverageProbe> auto& p) {
  io(p.pou), io(p.loc), io(p.kind), io(p.arm), io(p.arms), io(p.name);
}
template <class Io> void members(Io& io, Is<CoverageTable> auto& c) { io(c.counterAddress), io(c.probes); }
template <class Io> void members(Io& io, Is<Module> auto& m) {
  io.section("code"), io(m.code), io(m.constants), io(m.indexes);
  io.section("pous"), io(m.pous), io(m.lines), io(m.files);
  io.section("types"), io(m.types);
  io.section("symbols"), io(m.symbols), io(m.programs), io(m.tasks);
  io.section("image"), io(m.initialImage), io(m.staticSize), io(m.writableEnd), io(m.stackSize), io(m.maxCallDepth),
      io(m.registerStackSize), io(m.inputs), io(m.outputs), io(m.memory), io(m.initPou), io(m.exitPou);
  io.section("coverage"), io(m.coverage);
}

// Vectors of these are copied as their bytes: the bulk of a module, and every byte pattern is
// a value (an opcode out of range is the verifier's to refuse).
template <class T>
concept Bulk = Is<T, Instr> || Is<T, uint64_t> || Is<T, uint8_t> || Is<T, uint32_t>;

class Writer {
 public:
  std::string bytes;

  void section(std::string_view) {}
  template <Scalar T> void operator()(const T& v) { bytes.append(reinterpret_cast<const char*>(&v), sizeof v); }
  void operator()(const std::string& s) {
    (*this)(static_cast<uint32_t>(s.size()));
    bytes += s;
  }
  template <class T> void operator()(const std::vector<T>& v) {
    (*this)(static_cast<uint32_t>(v.size()));
    if constexpr (Bulk<T>) {
      bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    } else {
      for (const T& item : v) (*this)(item);
    }
  }
  template <class T> void operator()(const T& v) requires(!Scalar<T>) { members(*this, v); }
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  // The first problem, "" while there is none; after one, every read yields zeros.
  const std::string& problem() const { return problem_; }
  bool atEnd() const { return at_ == bytes_.size(); }

  void section(std::string_view name) { section_ = name; }
  template <Scalar T> void operator()(T& v) {
    v = T{};
    if constexpr (std::is_enum_v<T> || Is<T, bool>) {
      // A byte read as it is could be no value of the type at all (a bool of 2 is undefined).
      static_assert(sizeof(T) == 1);
      uint8_t byte = 0;
      if (!take(&byte, 1)) return;
      if (byte > lastValue(T{})) {
        fail("a value out of range in '" + std::string(section_) + "'");
        return;
      }
      v = static_cast<T>(byte);
    } else {
      take(&v, sizeof v);
    }
  }
  void operator()(std::string& s) {
    const uint32_t n = count(1);
    s.assign(n, '\0');
    take(s.data(), n);
  }
  template <class T> void operator()(std::vector<T>& v) {
    if constexpr (Bulk<T>) {
      v.resize(count(sizeof(T)));
      take(v.data(), v.size() * sizeof(T));
    } else {
      // Every element takes at least one byte: a count beyond what is left is a broken file,
      // refused before it can size a vector.
      v.resize(count(1));
      for (T& item : v) (*this)(item);
    }
  }
  template <class T> void operator()(T& v) requires(!Scalar<T>) { members(*this, v); }

 private:
  uint32_t count(size_t bytesEach) {
    uint32_t n = 0;
    (*this)(n);
    if (n > (bytes_.size() - at_) / bytesEach) {
      truncated();
      return 0;
    }
    return n;
  }
  bool take(void* to, size_t n) {
    if (!problem_.empty()) return false;
    if (n > bytes_.size() - at_) return truncated();
    if (n) std::memcpy(to, bytes_.data() + at_, n);
    at_ += n;
    return true;
  }
  bool truncated() { return fail("truncated in '" + std::string(section_) + "'"); }
  bool fail(std::string why) {
    if (problem_.empty()) problem_ = std::move(why);
    at_ = bytes_.size();
    return false;
  }

  std::string_view bytes_;
  size_t at_ = 0;
  std::string_view section_ = "header";
  std::string problem_;
};

}  // namespace

std::string encodeModule(const Module& m) {
  Writer w;
  w.bytes = kMagic;
  w(kFormatVersion);
  w(m);
  w(hashText(w.bytes));
  return std::move(w.bytes);
}

std::string decodeModule(std::string_view bytes, Module& out) {
  if (bytes.size() < kMagic.size() + sizeof kFormatVersion + kChecksumBytes || bytes.substr(0, kMagic.size()) != kMagic)
    return "not a virtcom module file";
  const std::string_view body = bytes.substr(0, bytes.size() - kChecksumBytes);
  uint64_t checksum = 0;
  std::memcpy(&checksum, bytes.data() + body.size(), kChecksumBytes);
  if (checksum != hashText(body)) return "checksum mismatch";
  Reader r(body.substr(kMagic.size()));
  uint32_t version = 0;
  r(version);
  if (version != kFormatVersion) return "format version " + std::to_string(version) + ", expected " + std::to_string(kFormatVersion);
  r(out);
  if (!r.problem().empty()) return r.problem();
  if (!r.atEnd()) return "bytes left after the module";
  return {};
}

}  // namespace virtcom::bc
