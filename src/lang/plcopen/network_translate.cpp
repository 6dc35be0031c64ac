// LD/FBD networks to ST statements; the rules are in network_translate.hpp.
#include "lang/plcopen/network_translate.hpp"

#include <algorithm>
#include <limits>

#include "core/ascii.hpp"
#include "lang/plcopen/diagnostic_codes.hpp"
#include "lang/plcopen/jump_sections.hpp"

namespace virtcom::plcopen::detail {

namespace {

// Longest chain of elements (and widest wired OR) translated; deeper networks are reported.
constexpr int kMaxChain = 256;

bool isTrueLiteral(const st::Expr& e) { return e.kind == st::ExprKind::BoolLit && e.intValue == 1; }

class Translator {
 public:
  Translator(Importer& imp, const Network& net, st::Pou& owner, std::string_view prefix)
      : imp_(imp), b_(imp.build()), net_(net), owner_(owner), prefix_(prefix),
        state_(net.elements.size(), State::Unvisited), cached_(net.elements.size()), parsed_(net.elements.size()) {
    memories_.section = st::VarSection::Var;
    // An action's body runs in its own frame, without the VAR_TEMPs of the POU that holds its
    // hidden variables (an action declares none): its intermediate values are plain VARs.
    temps_.section = prefix.empty() ? st::VarSection::Temp : st::VarSection::Var;
  }

  st::StmtList run();
  st::ExprPtr condition(size_t i, st::StmtList& before);

 private:
  void addHiddenVariables();
  enum class State : uint8_t { Unvisited, InProgress, Done };

  // ---- values ----
  st::ExprPtr valueOf(const Connection& conn, const Element& consumer);
  st::ExprPtr pinValue(const Pin& pin, const Element& consumer);
  st::ExprPtr requiredInput(const Element& e, size_t pin, std::string_view what);
  st::ExprPtr contactValue(size_t i);
  st::ExprPtr connectorValue(size_t i);
  st::ExprPtr blockOutput(size_t i, const Connection& conn);
  st::ExprPtr functionCall(size_t i);
  st::ExprPtr variableOf(size_t i);
  st::ExprPtr inOutOutput(size_t i);
  st::ExprPtr edgeDetect(st::ExprPtr signal, Edge edge, const std::string& memoryName, SourceLocation loc);
  st::ExprPtr shared(st::ExprPtr value, uint32_t localId, size_t consumers);
  st::ExprPtr loopError(const Element& e);

  // ---- statements ----
  void execute(size_t i);
  void executeBlock(size_t i);
  void executeAssignment(size_t i);
  void executeCoil(size_t i);
  void executeJump(size_t i);
  void emit(st::StmtPtr stmt);
  std::vector<size_t> executionOrder() const;
  std::string hidden(std::string_view role, uint32_t localId, std::string_view type, bool temp, SourceLocation loc);
  const Pin* enablePin(const Element& e) const;

  Importer& imp_;
  AstBuilder& b_;
  const Network& net_;
  st::Pou& owner_;
  std::string prefix_;
  std::vector<State> state_;
  std::vector<st::ExprPtr> cached_;   // an element's output, to be cloned by every reader
  std::vector<st::ExprPtr> parsed_;   // the element's <variable>/<expression>, parsed once
  std::vector<st::ExprPtr> guards_;   // EN conditions of the functions inlined into the value being built
  std::vector<std::string> labels_;   // section k starts at labels_[k - 1]
  st::StmtList* out_ = nullptr;
  std::string jumpVar_;
  st::VarBlock memories_, temps_;
  int depth_ = 0;
  bool tooDeep_ = false;
};

std::string Translator::hidden(std::string_view role, uint32_t localId, std::string_view type, bool temp,
                               SourceLocation loc) {
  std::string name = "__" + prefix_ + std::string(role) + std::to_string(localId);
  st::VarDecl decl;
  decl.names.push_back({name, loc});
  decl.type.name = std::string(type);
  decl.type.loc = loc;
  decl.loc = loc;
  (temp ? temps_ : memories_).vars.push_back(std::move(decl));
  return name;
}

void Translator::emit(st::StmtPtr stmt) {
  if (!guards_.empty()) {
    st::ExprPtr cond = std::move(guards_.front());
    for (size_t k = 1; k < guards_.size(); ++k) cond = b_.binary(st::BinaryOp::And, std::move(cond), std::move(guards_[k]));
    guards_.clear();
    st::StmtList body;
    body.push_back(std::move(stmt));
    stmt = b_.ifThen(std::move(cond), std::move(body));
  }
  out_->push_back(std::move(stmt));
}

st::ExprPtr Translator::loopError(const Element& e) {
  imp_.error(diag::X009, e.node, describe(e.node) + " is part of a loop of connections; only a loop through a "
                                                    "function block instance or an in-out variable (feedback) is allowed");
  return b_.boolLit(false, imp_.xml().at(e.node));
}

st::ExprPtr Translator::variableOf(size_t i) {
  const Element& e = net_.elements[i];
  if (!parsed_[i]) {
    bool ladder = e.kind == ElementKind::Contact || e.kind == ElementKind::Coil;
    parsed_[i] = imp_.expressionChild(e.node, ladder ? "variable" : "expression");
    if (!parsed_[i]) parsed_[i] = b_.name("", imp_.xml().at(e.node));
  }
  return b_.clone(*parsed_[i]);
}

// Rising: signal AND NOT memory; falling: NOT signal AND memory; then memory := signal.
st::ExprPtr Translator::edgeDetect(st::ExprPtr signal, Edge edge, const std::string& memoryName, SourceLocation loc) {
  std::string pulse = memoryName + "_pulse";
  st::VarDecl decl;
  decl.names.push_back({pulse, loc});
  decl.type.name = "BOOL";
  decl.type.loc = loc;
  decl.loc = loc;
  temps_.vars.push_back(std::move(decl));
  st::ExprPtr now = b_.clone(*signal);
  st::ExprPtr before = b_.name(memoryName, loc);
  st::ExprPtr value = edge == Edge::Rising ? b_.binary(st::BinaryOp::And, std::move(now), b_.notOf(std::move(before)))
                                           : b_.binary(st::BinaryOp::And, b_.notOf(std::move(now)), std::move(before));
  out_->push_back(b_.assign(b_.name(pulse, loc), std::move(value)));
  out_->push_back(b_.assign(b_.name(memoryName, loc), std::move(signal)));
  return b_.name(pulse, loc);
}

// A value read by several elements is computed once into a hidden BOOL temporary.
st::ExprPtr Translator::shared(st::ExprPtr value, uint32_t localId, size_t consumers) {
  if (consumers <= 1 || value->kind == st::ExprKind::Name || value->kind == st::ExprKind::BoolLit) return value;
  SourceLocation loc = value->loc;
  std::string tmp = hidden("flow", localId, "BOOL", true, loc);
  out_->push_back(b_.assign(b_.name(tmp, loc), std::move(value)));
  return b_.name(tmp, loc);
}

st::ExprPtr Translator::pinValue(const Pin& pin, const Element& consumer) {
  if (pin.sources.size() > static_cast<size_t>(kMaxChain)) {
    imp_.unsupported(pin.node, "more than " + std::to_string(kMaxChain) + " connections into one input");
    return b_.boolLit(false, imp_.xml().at(pin.node));
  }
  st::ExprPtr value;
  for (const Connection& conn : pin.sources) {
    st::ExprPtr v = valueOf(conn, consumer);
    if (!value) value = std::move(v);
    else if (isTrueLiteral(*value) || isTrueLiteral(*v)) value = b_.boolLit(true, value->loc);
    else value = b_.binary(st::BinaryOp::Or, std::move(value), std::move(v));
  }
  if (!value) return nullptr;
  if (pin.negated) value = b_.notOf(std::move(value));
  if (pin.edge != Edge::None) {
    std::string memory = hidden("edge" + pin.formal + "_", consumer.localId, "BOOL", false, value->loc);
    value = edgeDetect(std::move(value), pin.edge, memory, imp_.xml().at(pin.node));
  }
  return value;
}

st::ExprPtr Translator::requiredInput(const Element& e, size_t pin, std::string_view what) {
  if (pin < e.inputs.size())
    if (st::ExprPtr v = pinValue(e.inputs[pin], e)) return v;
  imp_.error(diag::X008, pin < e.inputs.size() ? e.inputs[pin].node : e.node,
             describe(e.node) + ": " + std::string(what) + " is not connected");
  return b_.boolLit(false, imp_.xml().at(e.node));
}

st::ExprPtr Translator::valueOf(const Connection& conn, const Element& consumer) {
  // Every level of a chain of elements is a level of expression nesting; bound it like the parser does.
  struct DepthGuard {
    int& depth;
    explicit DepthGuard(int& d) : depth(++d) {}
    ~DepthGuard() { --depth; }
  } guard(depth_);
  if (depth_ > kMaxChain) {
    if (!tooDeep_) imp_.unsupported(consumer.node, "a chain of more than " + std::to_string(kMaxChain) + " connected elements");
    tooDeep_ = true;
    return b_.boolLit(false, imp_.xml().at(conn.node));
  }
  size_t i = net_.find(conn.refLocalId);
  if (i == kNoElement) {
    imp_.error(diag::X006, conn.node, describe(consumer.node) + ": the connection refers to localId " +
                                          std::to_string(conn.refLocalId) + ", which is no element of this body");
    return b_.boolLit(false, imp_.xml().at(conn.node));
  }
  const Element& e = net_.elements[i];
  switch (e.kind) {
    case ElementKind::LeftRail: return b_.boolLit(true, imp_.xml().at(e.node));
    case ElementKind::Contact: return contactValue(i);
    case ElementKind::Connector: return connectorValue(i);
    case ElementKind::Block: return blockOutput(i, conn);
    case ElementKind::InVariable: {
      st::ExprPtr v = variableOf(i);
      return e.negated ? b_.notOf(std::move(v)) : std::move(v);
    }
    case ElementKind::InOutVariable:
      // A loop through a variable (Beremiz's counters: Cnt feeds ADD, which feeds Cnt) reads
      // the variable as the previous statements left it, as IEC feedback does.
      if (state_[i] == State::InProgress) return inOutOutput(i);
      execute(i);
      return cached_[i] ? b_.clone(*cached_[i]) : b_.boolLit(false, imp_.xml().at(e.node));
    case ElementKind::Coil:
      if (state_[i] == State::InProgress) return loopError(e);
      execute(i);
      return cached_[i] ? b_.clone(*cached_[i]) : b_.boolLit(false, imp_.xml().at(e.node));
    case ElementKind::Continuation:
      imp_.error(diag::X006, e.node, describe(e.node) + ": there is no connector named '" + e.name + "' in this body");
      return b_.boolLit(false, imp_.xml().at(e.node));
    default:
      imp_.error(diag::X006, conn.node, describe(consumer.node) + " reads " + describe(e.node) + ", which has no output");
      return b_.boolLit(false, imp_.xml().at(conn.node));
  }
}

st::ExprPtr Translator::contactValue(size_t i) {
  const Element& e = net_.elements[i];
  if (state_[i] == State::InProgress) return loopError(e);
  if (state_[i] == State::Unvisited) {
    state_[i] = State::InProgress;
    st::ExprPtr power = requiredInput(e, 0, "the contact's left side");
    st::ExprPtr term = variableOf(i);
    if (e.edge != Edge::None) {
      std::string memory = hidden("edge", e.localId, "BOOL", false, term->loc);
      term = edgeDetect(std::move(term), e.edge, memory, imp_.xml().at(e.node));
    } else if (e.negated) {
      term = b_.notOf(std::move(term));
    }
    st::ExprPtr value = isTrueLiteral(*power) ? std::move(term) : b_.binary(st::BinaryOp::And, std::move(power), std::move(term));
    cached_[i] = shared(std::move(value), e.localId, e.consumers);
    state_[i] = State::Done;
  }
  return b_.clone(*cached_[i]);
}

st::ExprPtr Translator::connectorValue(size_t i) {
  const Element& e = net_.elements[i];
  if (state_[i] == State::InProgress) return loopError(e);
  if (state_[i] == State::Unvisited) {
    state_[i] = State::InProgress;
    cached_[i] = requiredInput(e, 0, "the connector's input");
    state_[i] = State::Done;
  }
  return b_.clone(*cached_[i]);
}

const Pin* Translator::enablePin(const Element& e) const {
  for (const Pin& pin : e.inputs)
    if (iequalsAscii(pin.formal, "EN")) return &pin;
  return nullptr;
}

st::ExprPtr Translator::blockOutput(size_t i, const Connection& conn) {
  const Element& e = net_.elements[i];
  const BlockOutput* out = nullptr;
  for (const BlockOutput& o : e.outputs)
    if (conn.formal.empty() ? !iequalsAscii(o.formal, "ENO") : iequalsAscii(o.formal, conn.formal)) {
      out = &o;
      break;
    }
  if (!out) {
    imp_.error(diag::X006, conn.node, describe(e.node) + " ('" + e.name + "') has no output '" + conn.formal + "'");
    return b_.boolLit(false, imp_.xml().at(conn.node));
  }
  SourceLocation loc = imp_.xml().at(e.node);
  st::ExprPtr value;
  if (iequalsAscii(out->formal, "ENO")) {
    const Pin* en = enablePin(e);
    if (!e.instanceName.empty() && en && !en->sources.empty()) {
      if (state_[i] == State::Unvisited) execute(i);
      value = b_.name("__" + prefix_ + "eno" + std::to_string(e.localId), loc);
    } else {
      value = en ? pinValue(*en, e) : nullptr;
      if (!value) value = b_.boolLit(true, loc);
    }
  } else if (e.instanceName.empty()) {
    auto result = std::find_if(e.outputs.begin(), e.outputs.end(), [](const BlockOutput& o) { return !iequalsAscii(o.formal, "ENO"); });
    if (&*result != out && !out->inOut) {
      imp_.unsupported(e.node, "reading output '" + out->formal + "' of function '" + e.name +
                                   "' (only the function's result can be connected)");
      return b_.boolLit(false, loc);
    }
    value = functionCall(i);
  } else if (out->inOut) {
    if (state_[i] == State::Unvisited) execute(i);
    for (const Pin& pin : e.inputs)
      if (pin.formal == out->formal && !value) value = pinValue(pin, e);
    if (!value) value = b_.boolLit(false, loc);
  } else {
    // A block still being evaluated is read through a feedback path: its previous outputs.
    if (state_[i] == State::Unvisited) execute(i);
    value = b_.member(b_.name(e.instanceName, loc), out->formal, loc);
  }
  return out->negated ? b_.notOf(std::move(value)) : std::move(value);
}

// Functions are inlined where their result is read: positional arguments in the order of the
// block's inputs (MOVE is its input); EN becomes a guard on the statement reading the result.
st::ExprPtr Translator::functionCall(size_t i) {
  const Element& e = net_.elements[i];
  if (state_[i] == State::InProgress) return loopError(e);
  state_[i] = State::InProgress;
  SourceLocation loc = imp_.xml().at(e.node);
  st::ExprPtr call = b_.expr(st::ExprKind::Call, loc);
  call->lhs = b_.name(e.name, loc);
  for (size_t k = 0; k < e.inputs.size(); ++k) {
    const Pin& pin = e.inputs[k];
    if (iequalsAscii(pin.formal, "EN")) {
      if (st::ExprPtr en = pinValue(pin, e); en && !isTrueLiteral(*en)) guards_.push_back(std::move(en));
      continue;
    }
    st::CallArg arg;
    arg.loc = imp_.xml().at(pin.node);
    arg.value = requiredInput(e, k, "input '" + pin.formal + "'");
    call->args.push_back(std::move(arg));
  }
  state_[i] = State::Unvisited;  // read again, it is inlined again
  if (iequalsAscii(e.name, "MOVE") && call->args.size() == 1) return std::move(call->args.front().value);
  return call;
}

void Translator::execute(size_t i) {
  if (state_[i] != State::Unvisited) return;
  state_[i] = State::InProgress;
  switch (net_.elements[i].kind) {
    case ElementKind::Block: executeBlock(i); break;
    case ElementKind::Coil: executeCoil(i); break;
    case ElementKind::OutVariable: case ElementKind::InOutVariable: executeAssignment(i); break;
    case ElementKind::Jump: case ElementKind::Return: executeJump(i); break;
    default: break;
  }
  state_[i] = State::Done;
}

void Translator::executeBlock(size_t i) {
  const Element& e = net_.elements[i];
  SourceLocation loc = imp_.xml().at(e.node);
  if (e.instanceName.empty()) {
    if (e.consumers > 0) return;  // inlined where read
    state_[i] = State::Unvisited;
    st::ExprPtr call = functionCall(i);
    if (call->kind == st::ExprKind::Call) emit(b_.callStmt(std::move(call)));
    return;
  }
  st::ExprPtr en;
  st::ExprPtr call = b_.expr(st::ExprKind::Call, loc);
  call->lhs = b_.name(e.instanceName, loc);
  for (const Pin& pin : e.inputs) {
    st::ExprPtr v = pinValue(pin, e);
    if (iequalsAscii(pin.formal, "EN")) {
      en = std::move(v);
      continue;
    }
    if (!v) continue;  // an unconnected input keeps its value (IEC 61131-3 6.6.1.3)
    st::CallArg arg;
    arg.name = pin.formal;
    arg.loc = imp_.xml().at(pin.node);
    arg.value = std::move(v);
    call->args.push_back(std::move(arg));
  }
  if (!en) {
    emit(b_.callStmt(std::move(call)));
    return;
  }
  std::string eno = hidden("eno", e.localId, "BOOL", false, loc);
  emit(b_.assign(b_.name(eno, loc), std::move(en)));
  st::StmtList body;
  body.push_back(b_.callStmt(std::move(call)));
  emit(b_.ifThen(b_.name(eno, loc), std::move(body)));
}

void Translator::executeAssignment(size_t i) {
  const Element& e = net_.elements[i];
  st::ExprPtr value = requiredInput(e, 0, "the variable's input");
  if (e.negated) value = b_.notOf(std::move(value));
  emit(b_.assign(variableOf(i), std::move(value)));
  if (e.kind == ElementKind::InOutVariable) cached_[i] = inOutOutput(i);
}

st::ExprPtr Translator::inOutOutput(size_t i) {
  st::ExprPtr v = variableOf(i);
  return net_.elements[i].negatedOut ? b_.notOf(std::move(v)) : std::move(v);
}

void Translator::executeCoil(size_t i) {
  const Element& e = net_.elements[i];
  st::ExprPtr power = requiredInput(e, 0, "the coil's left side");
  if (e.consumers > 0) {
    power = shared(std::move(power), e.localId, 2);
    cached_[i] = b_.clone(*power);
  }
  st::ExprPtr target = variableOf(i);
  power->loc = imp_.xml().at(e.node);  // a type error in the coil's assignment points at the coil
  if (e.storage != Storage::None) {
    emit(b_.assign(std::move(target), std::move(power), e.storage == Storage::Set ? st::StmtKind::SetAssign : st::StmtKind::ResetAssign));
    return;
  }
  if (e.edge != Edge::None) power = edgeDetect(std::move(power), e.edge, hidden("edge", e.localId, "BOOL", false, target->loc), imp_.xml().at(e.node));
  else if (e.negated) power = b_.notOf(std::move(power));
  emit(b_.assign(std::move(target), std::move(power)));
}

void Translator::executeJump(size_t i) {
  const Element& e = net_.elements[i];
  SourceLocation loc = imp_.xml().at(e.node);
  st::ExprPtr cond = requiredInput(e, 0, e.kind == ElementKind::Jump ? "the jump's condition" : "the return's condition");
  st::StmtList body;
  if (e.kind == ElementKind::Return) {
    body.push_back(b_.simple(st::StmtKind::Return, loc));
  } else {
    auto label = std::find_if(labels_.begin(), labels_.end(), [&](const std::string& l) { return iequalsAscii(l, e.name); });
    if (label == labels_.end()) {
      imp_.error(diag::X010, e.node, describe(e.node) + ": there is no label '" + e.name + "' in this body");
      return;
    }
    if (jumpVar_.empty()) jumpVar_ = hidden("jump", 0, "INT", true, loc);
    body = jumpToSection(b_, jumpVar_, static_cast<size_t>(label - labels_.begin()) + 1, loc);
  }
  if (isTrueLiteral(*cond)) {
    for (auto& s : body) emit(std::move(s));
  } else {
    emit(b_.ifThen(std::move(cond), std::move(body)));
  }
}

std::vector<size_t> Translator::executionOrder() const {
  std::vector<size_t> order;
  bool allPositioned = true;
  for (size_t i = 0; i < net_.elements.size(); ++i) {
    const Element& e = net_.elements[i];
    switch (e.kind) {
      case ElementKind::Block: case ElementKind::Coil: case ElementKind::OutVariable: case ElementKind::InOutVariable:
      case ElementKind::Jump: case ElementKind::Return: case ElementKind::Label:
        order.push_back(i);
        allPositioned = allPositioned && e.positioned;
        break;
      default: break;
    }
  }
  constexpr uint32_t kUnordered = std::numeric_limits<uint32_t>::max();
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const Element& x = net_.elements[a];
    const Element& y = net_.elements[b];
    uint32_t ox = x.executionOrder ? x.executionOrder : kUnordered, oy = y.executionOrder ? y.executionOrder : kUnordered;
    if (ox != oy) return ox < oy;
    if (allPositioned && x.y != y.y) return x.y < y.y;
    if (allPositioned && x.x != y.x) return x.x < y.x;
    return false;
  });
  return order;
}

st::StmtList Translator::run() {
  std::vector<size_t> order = executionOrder();
  for (size_t i : order)
    if (net_.elements[i].kind == ElementKind::Label) labels_.push_back(net_.elements[i].name);
  std::vector<st::StmtList> sections(1);
  for (size_t i : order) {
    if (net_.elements[i].kind == ElementKind::Label) {
      sections.emplace_back();
      continue;
    }
    out_ = &sections.back();
    execute(i);
  }
  st::StmtList body = joinSections(b_, std::move(sections), jumpVar_, owner_.loc);
  addHiddenVariables();
  return body;
}

// A function's EN in the condition's path gates the value as it gates an assignment: the
// transition does not clear while EN is FALSE.
st::ExprPtr Translator::condition(size_t i, st::StmtList& before) {
  out_ = &before;
  st::ExprPtr value = requiredInput(net_.elements[i], 0, "the transition's condition");
  for (st::ExprPtr& guard : guards_) value = b_.binary(st::BinaryOp::And, std::move(guard), std::move(value));
  guards_.clear();
  addHiddenVariables();
  return value;
}

void Translator::addHiddenVariables() {
  if (!memories_.vars.empty()) owner_.varBlocks.push_back(std::move(memories_));
  if (!temps_.vars.empty()) owner_.varBlocks.push_back(std::move(temps_));
}

}  // namespace

st::StmtList translateNetwork(Importer& imp, const Network& net, st::Pou& owner, std::string_view prefix) {
  return Translator(imp, net, owner, prefix).run();
}

st::ExprPtr translateCondition(Importer& imp, const Network& net, uint32_t transitionId, st::Pou& owner,
                               std::string_view prefix, st::StmtList& before) {
  size_t i = net.find(transitionId);
  // No such element: the transition's localId was missing, malformed or taken (reported).
  if (i == kNoElement || net.elements[i].kind != ElementKind::Condition) return imp.build().boolLit(false, owner.loc);
  return Translator(imp, net, owner, prefix).condition(i, before);
}

}  // namespace virtcom::plcopen::detail
