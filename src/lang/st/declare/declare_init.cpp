// Declaration pass, part 3: global variables, located variables, the configuration (tasks and
// program instances), initial values of everything static, and frame templates.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/iec_value.hpp"
#include "lang/st/declare/declare.hpp"
#include "lang/syntax/diagnostic_codes.hpp"
#include "lang/st/parse/lexer.hpp"

namespace virtcom::st {

namespace {
// Each process image area is as large as its located variables need, and at least this large
// (room for direct addresses used in code and for protocol access), at most kMaxArea (TwinCAT's
// %M offsets run to 0xFFFF: docs/ads.md, Process image areas).
constexpr uint32_t kMinAreaSize = 256;
constexpr uint32_t kMaxAreaSize = 65536;
// Room left for a located struct or FB, whose size is not known before types are laid out.
constexpr uint32_t kUnknownTypeRoom = 64;
}  // namespace

// The bytes a located declaration's type takes, as far as it can be known before types are laid
// out: elementary types, strings and arrays of them with constant bounds exactly (Beckhoff's test
// project declares `ARRAY[0..1027] OF BYTE AT %MB0`), other types kUnknownTypeRoom; placeLocated
// checks the real extent later.
uint32_t Declarer::locatedSizeEstimate(const TypeSpec& t) {
  switch (t.kind) {
    case TypeSpecKind::Named: {
      ElemType e;
      return elemTypeByName(t.name, e) && elemTypeInfo(e).sizeBytes ? elemTypeInfo(e).sizeBytes : kUnknownTypeRoom;
    }
    case TypeSpecKind::String: {
      uint64_t length = 80;
      if (t.length)
        if (auto v = constant(*t.length, nullptr, true); v && v->kind == ConstValue::Kind::Int && v->i > 0) length = static_cast<uint64_t>(v->i);
      return static_cast<uint32_t>(std::min<uint64_t>((length + 1) * (t.wide ? 2 : 1), kMaxAreaSize));
    }
    case TypeSpecKind::Array: {
      uint64_t count = 1;
      for (const ArrayRange& d : t.dims) {
        auto lo = d.lo ? constant(*d.lo, nullptr, true) : std::nullopt;
        auto hi = d.hi ? constant(*d.hi, nullptr, true) : std::nullopt;
        if (!lo || !hi || lo->kind != ConstValue::Kind::Int || hi->kind != ConstValue::Kind::Int || hi->i < lo->i)
          return kUnknownTypeRoom;
        count = std::min<uint64_t>(count * static_cast<uint64_t>(hi->i - lo->i + 1), kMaxAreaSize);
      }
      const uint64_t element = t.element ? locatedSizeEstimate(*t.element) : kUnknownTypeRoom;
      return static_cast<uint32_t>(std::min<uint64_t>(count * element, kMaxAreaSize));
    }
    default: return 8;  // pointers, references, subranges and enums of elementary bases
  }
}

std::optional<DirectAddress> parseDirectAddress(std::string_view text) {
  std::string t = upper(text);
  if (t.size() < 3 || t[0] != '%') return std::nullopt;  // %I5 is the shortest form
  DirectAddress a;
  a.area = t[1];
  if (a.area != 'I' && a.area != 'Q' && a.area != 'M') return std::nullopt;
  size_t i = 2;
  char sizeChar = 'X';
  if (std::isalpha(static_cast<unsigned char>(t[i]))) sizeChar = t[i++];
  auto number = [&](uint32_t& out) {
    if (i >= t.size() || !std::isdigit(static_cast<unsigned char>(t[i]))) return false;
    uint64_t v = 0;
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) {
      v = v * 10 + static_cast<uint64_t>(t[i++] - '0');
      if (v > 1u << 24) return false;
    }
    out = static_cast<uint32_t>(v);
    return true;
  };
  uint32_t first = 0;
  if (!number(first)) return std::nullopt;
  switch (sizeChar) {
    case 'X': {
      a.size = 1;
      if (i >= t.size()) {
        // IEC 61131-3's flat bit number (%IX1, %QX75, %I75): bit n is bit n MOD 8 of byte n / 8.
        a.byteOffset = first / 8;
        a.bit = static_cast<int8_t>(first % 8);
        break;
      }
      uint32_t bit = 0;
      if (t[i] != '.') return std::nullopt;
      ++i;
      if (!number(bit) || bit > 7) return std::nullopt;
      a.byteOffset = first;
      a.bit = static_cast<int8_t>(bit);
      break;
    }
    // CODESYS numbers B/W/D/L addresses in units of their own size: %IW2 starts at byte 4.
    case 'B': a.byteOffset = first; a.size = 1; break;
    case 'W': a.byteOffset = first * 2; a.size = 2; break;
    case 'D': a.byteOffset = first * 4; a.size = 4; break;
    case 'L': a.byteOffset = first * 8; a.size = 8; break;
    default: return std::nullopt;
  }
  if (i != t.size()) return std::nullopt;
  return a;
}

std::string directAddressError(std::string_view text) {
  const std::string t = upper(text);
  const size_t i = t.find_first_of("0123456789");  // %<area>[<size>]<n>.<n>...
  const bool numeric = t.starts_with('%') && (i == 2 || i == 3) && t.find_first_not_of("0123456789.", i) == std::string::npos;
  const bool bitSized = numeric && (i == 2 || t[2] == 'X');
  // More fields than the flat form has (X: byte.bit, the other sizes one number).
  if (numeric && std::count(t.begin() + static_cast<std::ptrdiff_t>(i), t.end(), '.') + 1 > (bitSized ? 2 : 1))
    return "'" + std::string(text) + "' is a hierarchical address: IEC 61131-3 leaves the meaning of its fields "
           "(rack, module, channel of an I/O configuration) to the implementation, and virtcom's process image is "
           "three flat byte areas; write a flat address (%" + t.substr(1, i - 1) + "<n>" +
           (bitSized ? ", %" + std::string(1, t[1]) + "X<byte>.<bit>" : std::string()) + ") or use VAR_CONFIG";
  return "'" + std::string(text) + "' is not a valid direct address (expected e.g. %IX0.0, %QW2, %MD4)";
}

void Declarer::placeLocated(VarInfo& v, const std::string& address) {
  auto a = parseDirectAddress(address);
  const bc::ProcessArea& area = !a ? module_.inputs
                                : a->area == 'I' ? module_.inputs
                                : a->area == 'Q' ? module_.outputs
                                                 : module_.memory;
  v.storage = Storage::Absolute;
  if (!a && address.ends_with('*')) {
    diags_.error(diag::E109, v.loc, "'" + address + "' has no address: complete it in the CONFIGURATION with "
                                    "VAR_CONFIG (inst." + v.name + " AT " + address.substr(0, address.size() - 1) +
                                    "... : type;)");
    return;
  }
  if (!a) {
    diags_.error(diag::E109, v.loc, directAddressError(address));
    return;
  }
  uint32_t size = types_[v.type].size;
  if (a->bit >= 0 && !types_.isBool(v.type)) {
    diags_.error(diag::E109, v.loc, "bit address '" + address + "' needs a BOOL variable");
    return;
  }
  if (a->byteOffset + std::max(size, 1u) > area.size) {
    diags_.error(diag::E109, v.loc, "'" + address + "' is outside the " + std::string(1, a->area) + " area (" +
                                        std::to_string(area.size) + " bytes)");
    return;
  }
  v.offset = area.address + a->byteOffset;
  v.bit = a->bit;
}

void Declarer::allocateProcessAreas() {
  uint32_t extent[3] = {kMinAreaSize, kMinAreaSize, kMinAreaSize};  // I, Q, M
  auto visit = [&](const std::vector<VarBlock>& blocks) {
    for (const auto& block : blocks)
      for (const auto& decl : block.vars) {
        if (decl.location.empty()) continue;
        auto a = parseDirectAddress(decl.location);
        if (!a) continue;
        int area = a->area == 'I' ? 0 : a->area == 'Q' ? 1 : 2;
        extent[area] = std::max(extent[area], a->byteOffset + locatedSizeEstimate(decl.type));
      }
  };
  for (const auto& unit : units_) {
    for (const auto& pou : unit.pous) visit(pou->varBlocks);
    for (const auto& gvl : unit.globals) visit(gvl.blocks);
    for (const auto& cfg : unit.configurations) {
      visit(cfg.globals);
      for (const auto& res : cfg.resources) visit(res.globals);
    }
  }
  for (auto& e : extent) e = std::min((e + 63) / 64 * 64, kMaxAreaSize);
  module_.inputs = {image_.allocate(extent[0], 8), extent[0]};
  module_.outputs = {image_.allocate(extent[1], 8), extent[1]};
  module_.memory = {image_.allocate(extent[2], 8), extent[2]};
}

void Declarer::collectGlobalConstants() {
  auto collect = [&](const VarBlock& block, const std::string& listName) {
    if (!block.constant) return;
    for (const auto& decl : block.vars) {
      if (!decl.init) continue;
      auto v = constant(*decl.init, nullptr, true);
      if (!v) continue;
      for (const auto& n : decl.names) {
        globalConstants_[upper(n.name)] = *v;
        if (!listName.empty()) globalConstants_[upper(listName) + "." + upper(n.name)] = *v;
      }
    }
  };
  for (int pass = 0; pass < 2; ++pass)  // a second pass resolves constants defined by later ones
    for (const auto& unit : units_) {
      for (const auto& gvl : unit.globals)
        for (const auto& block : gvl.blocks) collect(block, gvl.name);
      for (const auto& cfg : unit.configurations) {
        for (const auto& block : cfg.globals) collect(block, "");
        for (const auto& res : cfg.resources)
          for (const auto& block : res.globals) collect(block, "");
      }
      for (const auto& pou : unit.pous)
        if (pou->kind == PouKind::Program)
          for (const auto& block : pou->varBlocks)
            if (block.section == VarSection::Global) collect(block, "");
    }
}

void Declarer::declareGlobals() {
  auto declareBlock = [&](const VarBlock& block, const std::string& listName) {
    for (const auto& decl : block.vars) {
      TypeId type = resolveType(decl.type, nullptr);
      for (const auto& n : decl.names) {
        std::string key = upper(n.name);
        if (model_.globalIndex.count(key)) {
          diags_.error(diag::E105, n.loc, "global variable '" + n.name + "' is already declared");
          continue;
        }
        if (type == kNoType) continue;
        GlobalVar g;
        g.listName = listName;
        g.var = makeVar(n, decl, type, VarSection::Global, block);
        checkVariable(g.var);
        if (!decl.location.empty()) {
          placeLocated(g.var, decl.location);
        } else {
          g.var.storage = Storage::Absolute;
          g.var.offset = image_.allocate(types_[type].size, types_[type].align);
        }
        if (block.constant && types_.isScalar(type) && decl.init)
          if (auto c = constant(*decl.init, nullptr)) g.var.constValue = *c;
        size_t index = model_.globals.size();
        model_.globalIndex[key] = index;
        if (!listName.empty()) model_.globalIndex[upper(listName) + "." + key] = index;
        model_.globals.push_back(std::move(g));
        const GlobalVar& placed = model_.globals.back();
        if (placed.var.bit < 0) {
          writeInitial(type, image_.at(placed.var.offset), decl.init.get(), nullptr);
          applyDeclarationArgs(type, image_.at(placed.var.offset), decl, nullptr);
        } else if (decl.init) {
          if (auto c = constant(*decl.init, nullptr)) writeScalar(type, image_.at(placed.var.offset), *c, placed.var.bit);
        }
      }
    }
  };
  for (const auto& unit : units_) {
    for (const auto& gvl : unit.globals) {
      if (!gvl.name.empty()) model_.globalListNames.push_back(upper(gvl.name));
      for (const auto& block : gvl.blocks) declareBlock(block, gvl.name);
    }
    for (const auto& cfg : unit.configurations) {
      for (const auto& block : cfg.globals) declareBlock(block, "");
      for (const auto& res : cfg.resources)
        for (const auto& block : res.globals) declareBlock(block, "");
    }
    // IEC 61131-3 lets a PROGRAM declare globals (its FBs reach them through VAR_EXTERNAL);
    // nothing else may.
    for (const auto& pou : unit.pous)
      for (const auto& block : pou->varBlocks) {
        if (block.section != VarSection::Global) continue;
        if (pou->kind == PouKind::Program)
          declareBlock(block, "");
        else
          diags_.error(diag::E108, block.loc, "VAR_GLOBAL is only allowed in a PROGRAM, a CONFIGURATION, a RESOURCE "
                                              "or at the top level of a file (a global variable list)");
      }
  }
  // Located variables declared inside POUs need their initial values too.
  for (auto& sym : model_.pous)
    for (auto& v : sym->members)
      if (v.storage == Storage::Absolute && v.decl && v.decl->init)
        if (auto c = constant(*v.decl->init, sym.get())) writeScalar(v.type, image_.at(v.offset), *c, v.bit);
}

void Declarer::checkExternals() {
  for (const auto& sym : model_.pous) {
    if (!sym->ast) continue;
    for (const auto& block : sym->ast->varBlocks) {
      if (block.section != VarSection::External) continue;
      for (const auto& decl : block.vars) {
        TypeId type = resolveType(decl.type, sym.get());
        for (const auto& n : decl.names) {
          auto it = model_.globalIndex.find(upper(n.name));
          if (it == model_.globalIndex.end()) {
            diags_.error(diag::E201, n.loc, "VAR_EXTERNAL '" + n.name + "' names no global variable; declare it in a VAR_GLOBAL list");
            continue;
          }
          const VarInfo& global = model_.globals[it->second].var;
          if (type != kNoType && !sameType(types_, type, global.type))
            diags_.error(diag::E120, n.loc, "VAR_EXTERNAL '" + n.name + "' is declared " + types_.name(type) +
                                                " but the global variable is " + types_.name(global.type));
          else if (global.constant && !block.constant)
            diags_.error(diag::E120, n.loc, "the global variable '" + n.name + "' is CONSTANT; declare it in VAR_EXTERNAL CONSTANT");
          else if (!global.constant && block.constant)
            diags_.error(diag::E120, n.loc, "the global variable '" + n.name + "' is not CONSTANT; declare it in VAR_EXTERNAL without CONSTANT");
        }
      }
    }
  }
}

static int64_t intervalFromSettings(const TaskDecl& task, Declarer& d, Diagnostics& diags, int32_t& priority) {
  int64_t interval = 10'000'000;
  for (const auto& s : task.settings) {
    std::string key = upper(s.name);
    if (!s.value) continue;
    auto v = d.constant(*s.value, nullptr);
    if (!v) continue;
    if (key == "INTERVAL") {
      bool ltime = v->type == TypeTable::elem(ElemType::Ltime);
      interval = ltime ? v->i : v->i * 1'000'000;
      if (interval <= 0) diags.error(diag::E118, s.loc, "task INTERVAL must be positive");
    } else if (key == "PRIORITY") {
      priority = static_cast<int32_t>(v->i);
    }
  }
  return interval;
}

void Declarer::declareConfiguration() {
  auto addInstance = [&](const std::string& name, PouSym* pou, SourceLocation loc) -> bool {
    for (const auto& p : model_.programInstances)
      if (upper(p.name) == upper(name)) {
        diags_.error(diag::E105, loc, "program instance '" + name + "' is already declared");
        return false;
      }
    ProgramInstanceSym inst;
    inst.name = name;
    inst.pou = pou;
    inst.address = image_.allocate(types_[pou->instanceType].size, types_[pou->instanceType].align);
    writeInitial(pou->instanceType, image_.at(inst.address), nullptr, nullptr);
    model_.programInstances.push_back(inst);
    return true;
  };
  bool configured = false;
  for (const auto& unit : units_) {
    for (const auto& cfg : unit.configurations) {
      for (const auto& res : cfg.resources) {
        configured = true;
        for (const auto& t : res.tasks) {
          TaskSym task;
          task.name = t.name;
          task.intervalNs = intervalFromSettings(t, *this, diags_, task.priority);
          model_.tasks.push_back(task);
        }
        for (const auto& p : res.programs) {
          auto it = model_.pouByName.find(upper(p.typeName));
          if (it == model_.pouByName.end() || it->second->kind != PouKind::Program) {
            diags_.error(diag::E118, p.loc, "'" + p.typeName + "' is not a PROGRAM");
            continue;
          }
          if (!addInstance(p.instanceName, it->second, p.loc)) continue;
          std::string scheduled = p.instanceName;
          if (auto caller = model_.pouByName.find(upper(configCallerName(p.instanceName))); caller != model_.pouByName.end()) {
            scheduled = caller->second->name;
            addInstance(scheduled, caller->second, p.loc);
          }
          TaskSym* task = nullptr;
          for (auto& t : model_.tasks)
            if (upper(t.name) == upper(p.taskName)) task = &t;
          if (!task && !p.taskName.empty()) {
            diags_.error(diag::E118, p.loc, "unknown TASK '" + p.taskName + "'");
            continue;
          }
          if (!task) {
            // A program without WITH runs in a default cyclic task.
            if (model_.tasks.empty() || !model_.tasks.front().isDefault) {
              TaskSym def;
              def.name = "__DEFAULT";
              def.isDefault = true;
              model_.tasks.insert(model_.tasks.begin(), def);
            }
            task = &model_.tasks.front();
          }
          task->programInstances.push_back(upper(scheduled));
        }
      }
    }
  }
  if (configured) return;
  // No configuration: one 10 ms task running every PROGRAM in declaration order.
  TaskSym task;
  task.name = "MainTask";
  task.isDefault = true;
  for (auto& sym : model_.pous) {
    if (sym->kind != PouKind::Program || sym->owner || sym->isLibrary) continue;
    if (addInstance(sym->name, sym.get(), sym->ast->loc)) task.programInstances.push_back(upper(sym->name));
  }
  model_.tasks.push_back(task);
}

void Declarer::buildTemplates() {
  for (auto& sym : model_.pous) {
    if (sym->frameSize == 0 || sym->frameTemplate != 0) continue;
    std::vector<uint8_t> bytes(sym->frameSize, 0);
    for (const auto& v : sym->locals) {
      if (v.byReference) continue;
      writeInitial(v.type, bytes.data() + v.offset, v.decl ? v.decl->init.get() : nullptr, sym.get());
      if (v.decl) applyDeclarationArgs(v.type, bytes.data() + v.offset, *v.decl, sym.get());
    }
    sym->frameTemplate = image_.addData(bytes.data(), sym->frameSize, 8);
  }
}

const std::vector<uint8_t>& Declarer::defaultBytes(TypeId type) {
  if (auto it = defaults_.find(type); it != defaults_.end()) return it->second;
  // A type that contains itself by value has already been reported (or fails verification):
  // never recurse forever, and never copy a member's bytes past the end of its container.
  static const std::vector<uint8_t> kNone;
  if (!defaultsInProgress_.insert(type).second) return kNone;
  const bc::TypeDesc& d = types_[type];
  std::vector<uint8_t> bytes(d.size, 0);
  switch (d.kind) {
    case bc::TypeKind::Enum:
      if (!d.enumerators.empty()) {
        ConstValue v;
        v.kind = ConstValue::Kind::Int;
        v.i = d.enumerators.front().value;
        writeScalar(type, bytes.data(), v, -1);
      }
      break;
    case bc::TypeKind::Array: {
      const std::vector<uint8_t> element = defaultBytes(d.element);
      for (size_t off = 0; off + element.size() <= bytes.size() && !element.empty(); off += element.size())
        std::memcpy(bytes.data() + off, element.data(), element.size());
      break;
    }
    case bc::TypeKind::Struct: {
      auto fb = model_.fbByType.find(type);
      if (fb != model_.fbByType.end()) {
        PouSym& pou = *fb->second;
        if (pou.hasClassHeader) {
          uint32_t id = pou.classId;
          std::memcpy(bytes.data(), &id, 4);
        }
        for (const auto& m : pou.members) {
          if (m.storage != Storage::Instance || m.byReference) continue;
          const std::vector<uint8_t>& md = defaultBytes(m.type);
          if (md.empty() || m.offset > bytes.size() || md.size() > bytes.size() - m.offset) continue;
          std::memcpy(bytes.data() + m.offset, md.data(), md.size());
          if (m.decl && m.decl->init) applyInit(m.type, bytes.data() + m.offset, *m.decl->init, &pou);
          if (m.decl) applyDeclarationArgs(m.type, bytes.data() + m.offset, *m.decl, &pou);
        }
      } else {
        for (const auto& f : d.fields) {
          const std::vector<uint8_t> fd = defaultBytes(f.type);
          if (fd.empty() || f.offset > bytes.size() || fd.size() > bytes.size() - f.offset) continue;
          std::memcpy(bytes.data() + f.offset, fd.data(), fd.size());
        }
        if (auto it = fieldInits_.find(type); it != fieldInits_.end())
          for (const auto& [index, init] : it->second)
            if (d.fields[index].offset + uint64_t{types_[d.fields[index].type].size} <= bytes.size())
              applyInit(d.fields[index].type, bytes.data() + d.fields[index].offset, *init, nullptr);
      }
      break;
    }
    default:
      if (auto sub = model_.subranges.find(type); sub != model_.subranges.end() && (sub->second.first > 0 || sub->second.second < 0)) {
        ConstValue v;
        v.kind = ConstValue::Kind::Int;
        v.i = sub->second.first;  // zero is outside the range: start at the lower bound
        writeScalar(type, bytes.data(), v, -1);
      }
      break;
  }
  if (auto it = typeInits_.find(type); it != typeInits_.end()) applyInit(type, bytes.data(), *it->second, nullptr);
  defaultsInProgress_.erase(type);
  return defaults_[type] = std::move(bytes);
}

void Declarer::writeInitial(TypeId type, uint8_t* dst, const Expr* init, const PouSym* pou) {
  const std::vector<uint8_t>& bytes = defaultBytes(type);
  std::memcpy(dst, bytes.data(), bytes.size());
  if (init) applyInit(type, dst, *init, pou);
}

bool Declarer::checkRange(TypeId type, const ConstValue& v, SourceLocation loc) {
  if (!types_.isInteger(type) || v.kind != ConstValue::Kind::Int) return true;
  ElemType e = types_.storageElem(type);
  uint32_t bits = bitWidth(e);
  bool ok;
  if (isSignedInt(e)) {
    int64_t lo = bits == 64 ? INT64_MIN : -(int64_t(1) << (bits - 1));
    int64_t hi = bits == 64 ? INT64_MAX : (int64_t(1) << (bits - 1)) - 1;
    ok = v.i >= lo && v.i <= hi;
  } else {
    ok = bits == 64 || (v.i >= 0 && static_cast<uint64_t>(v.i) < (uint64_t(1) << bits));
  }
  if (auto sub = model_.subranges.find(type); sub != model_.subranges.end())
    ok = ok && v.i >= sub->second.first && v.i <= sub->second.second;
  if (!ok) diags_.error(diag::E117, loc, "value " + std::to_string(v.i) + " is out of range for " + types_.name(type));
  return ok;
}

// A date or duration literal of another unit (DT#... for an LDT: seconds, not nanoseconds)
// would be stored unconverted; only TIME -> LTIME is scaled (writeScalar).
static bool initialTimeFits(const TypeTable& types, Diagnostics& diags, TypeId type, const ConstValue& v,
                            SourceLocation loc) {
  if (v.type == kNoType || v.type == type || !types.isElementary(type) || !types.isElementary(v.type)) return true;
  const ElemType to = types[type].elem, from = types[v.type].elem;
  const int64_t tu = timeUnitNs(to), fu = timeUnitNs(from);
  if (tu == 0 || fu == 0 || tu == fu || (from == ElemType::Time && to == ElemType::Ltime)) return true;
  diags.error(diag::E116, loc, "initial value: a " + types.name(v.type) + " literal counts in other units than " +
                                   types.name(type) + "; write a literal of type " + types.name(type) +
                                   " or convert in code (" + types.name(v.type) + "_TO_" + types.name(type) + ")");
  return false;
}

void Declarer::applyInit(TypeId type, uint8_t* dst, const Expr& init, const PouSym* pou) {
  const bc::TypeDesc& d = types_[type];
  if (init.kind == ExprKind::ArrayInit) {
    if (d.kind != bc::TypeKind::Array) {
      diags_.error(diag::E116, init.loc, "an array initialiser [...] needs an ARRAY variable, found " + d.name);
      return;
    }
    uint64_t count = d.size / std::max<uint32_t>(types_[d.element].size, 1);
    uint32_t elemSize = types_[d.element].size;
    uint64_t index = 0;
    for (const auto& item : init.items) {
      const Expr* value = item.get();
      uint64_t repeat = 1;
      if (item->kind == ExprKind::Repeat) {
        repeat = item->intValue;
        value = item->lhs.get();
      }
      for (uint64_t r = 0; r < repeat; ++r, ++index) {
        if (index >= count) {
          diags_.error(diag::E116, item->loc, "too many initial values: the array has " + std::to_string(count) + " elements");
          return;
        }
        if (value) applyInit(d.element, dst + index * elemSize, *value, pou);
      }
    }
    return;
  }
  if (init.kind == ExprKind::StructInit) {
    if (d.kind != bc::TypeKind::Struct) {
      diags_.error(diag::E116, init.loc, "a structure initialiser (a := ...) needs a STRUCT or FUNCTION_BLOCK variable, found " + d.name);
      return;
    }
    applyMemberInits(type, dst, init.args, pou);
    return;
  }
  if (d.kind == bc::TypeKind::Array || d.kind == bc::TypeKind::Struct) {
    diags_.error(diag::E116, init.loc, "'" + d.name + "' needs an initialiser in [...] or (name := ...) form");
    return;
  }
  if (d.kind == bc::TypeKind::Pointer || d.kind == bc::TypeKind::Reference) {
    // CODESYS code often spells out the initial value of pointers and interfaces, `itf : I_X := 0`.
    if (init.kind == ExprKind::IntLit)
      if (auto zero = constant(init, pou); zero && zero->i == 0) return;
    diags_.error(diag::E116, init.loc, "pointers, references and interfaces can only start as 0; assign them in code");
    return;
  }
  TypeId enumType = kNoType;
  std::optional<ConstValue> v;
  if (d.kind == bc::TypeKind::Enum && init.kind == ExprKind::Name) {
    v = bareEnumerator(init.text, enumType);
    if (!v) v = enumValue(d.name, init.text);
  }
  if (!v) v = constant(init, pou);
  if (!v) return;
  if (d.kind == bc::TypeKind::String) {
    if (v->kind != ConstValue::Kind::String) {
      diags_.error(diag::E116, init.loc, "a " + d.name + " needs a string literal as initial value");
      return;
    }
    std::memset(dst, 0, d.size);
    if (types_.isWideString(type)) {
      const std::u16string units = utf8ToUtf16(v->s);
      size_t n = std::min<size_t>(units.size(), d.stringLength);
      for (size_t i = 0; i < n; ++i) {
        dst[2 * i] = static_cast<uint8_t>(units[i] & 0xFF);
        dst[2 * i + 1] = static_cast<uint8_t>(units[i] >> 8);
      }
    } else {
      std::memcpy(dst, v->s.data(), std::min<size_t>(v->s.size(), d.stringLength));
    }
    return;
  }
  if (v->kind == ConstValue::Kind::String && types_.isChar(type)) {
    v = characterConstant(*v, d.elem);  // c : CHAR := 'a';
    if (!v) {
      diags_.error(diag::E116, init.loc, "a " + d.name + " starts from a literal of exactly one character (" +
                                             (d.elem == ElemType::Wchar ? "\"a\"" : "'a'") + ")");
      return;
    }
  }
  if (v->kind == ConstValue::Kind::String) {
    diags_.error(diag::E116, init.loc, "a string cannot initialise a " + d.name);
    return;
  }
  if (types_.isInteger(type) && v->kind == ConstValue::Kind::Real) {
    diags_.error(diag::E116, init.loc, "a REAL value cannot initialise a " + d.name + " (use REAL_TO_" + d.name + ")");
    return;
  }
  if (init.kind == ExprKind::Unary && init.unaryOp == UnaryOp::Not && types_.isInteger(type) && v->kind == ConstValue::Kind::Int) {
    // a bitwise NOT of an untyped literal takes the target's width: NOT 16#00FF -> 16#FF00
    uint32_t bits = types_.bits(type);
    if (bits < 64) v->i &= static_cast<int64_t>((uint64_t(1) << bits) - 1);
    if (types_.isSignedInt(type) && bits < 64 && (v->i >> (bits - 1)) & 1) v->i -= int64_t(1) << bits;
  }
  if (!initialTimeFits(types_, diags_, type, *v, init.loc)) return;
  checkRange(type, *v, init.loc);
  writeScalar(type, dst, *v, -1);
}

void Declarer::applyMemberInits(TypeId type, uint8_t* dst, const std::vector<CallArg>& args, const PouSym* pou) {
  const bc::TypeDesc& d = types_[type];
  for (const auto& arg : args) {
    const bc::Field* field = nullptr;
    for (const auto& f : d.fields)
      if (upper(f.name) == upper(arg.name)) field = &f;
    if (!field) {
      diags_.error(diag::E212, arg.loc, "'" + d.name + "' has no member '" + arg.name + "'");
      continue;
    }
    if (arg.value) applyInit(field->type, dst + field->offset, *arg.value, pou);
  }
}

void Declarer::applyDeclarationArgs(TypeId type, uint8_t* dst, const VarDecl& decl, const PouSym* pou) {
  if (decl.fbInitArgs.empty()) return;
  auto fb = model_.fbByType.find(type);
  if (fb == model_.fbByType.end() || fb->second->kind != PouKind::FunctionBlock) {
    diags_.error(diag::E116, decl.fbInitArgs.front().loc, "arguments in a declaration need a FUNCTION_BLOCK instance, found " + types_.name(type));
    return;
  }
  if (fb->second->methods.count("FB_INIT")) return;  // bound to FB_init's inputs by the init program
  for (const auto& arg : decl.fbInitArgs)
    if (arg.name.empty() || arg.output) {
      diags_.error(diag::E203, arg.loc, "arguments in a declaration are written name := value (inst : " + fb->second->name + "(a := 1))");
      return;
    }
  applyMemberInits(type, dst, decl.fbInitArgs, pou);
}

void Declarer::writeScalar(TypeId type, uint8_t* dst, const ConstValue& v, int8_t bit) {
  ElemType e = types_.storageElem(type);
  if (bit >= 0) {
    if (v.i) *dst = static_cast<uint8_t>(*dst | (1u << bit));
    else *dst = static_cast<uint8_t>(*dst & ~(1u << bit));
    return;
  }
  if (e == ElemType::Real) {
    float f = static_cast<float>(constAsReal(v));
    std::memcpy(dst, &f, 4);
    return;
  }
  if (e == ElemType::Lreal) {
    double f = constAsReal(v);
    std::memcpy(dst, &f, 8);
    return;
  }
  int64_t raw = constAsInt(v);
  if (e == ElemType::Ltime && v.type == TypeTable::elem(ElemType::Time)) raw *= 1'000'000;
  if (e == ElemType::Time && v.type == TypeTable::elem(ElemType::Ltime)) raw /= 1'000'000;
  if (e == ElemType::Bool) raw = raw != 0;
  uint32_t size = elemTypeInfo(e).sizeBytes;
  std::memcpy(dst, &raw, size);  // little endian: the low bytes
}

}  // namespace virtcom::st
