#pragma once
// Code generation: type-checks each POU body and emits its bytecode. One PouCompiler per POU;
// it reads the ProgramModel built by the Declarer and never edits the AST.
#include <optional>
#include <vector>

#include "bytecode/module.hpp"
#include "core/diagnostics.hpp"
#include "lang/st/declare/declare.hpp"

namespace virtcom::st {

struct CompileContext {
  ProgramModel& model;
  TypeTable& types;
  Declarer& declarer;
  bc::Module& module;
  ImageBuilder& image;
  Diagnostics& diags;
  bool coverage = false;  // emit coverage probes (CompileOptions::coverage)
};

inline constexpr uint16_t kAbsolute = 0xffff;  // Place::base for absolute addresses
inline constexpr uint16_t kNoReg = 0xffff;     // no register allocated
inline constexpr uint16_t kFp = 0;
inline constexpr uint16_t kThis = 1;

// Something addressable: a variable, a member, an array element, a dereferenced pointer.
struct Place {
  TypeId type = kNoType;
  uint16_t base = kAbsolute;  // register holding the base address, or kAbsolute
  uint32_t offset = 0;        // added to the base (absolute address when base == kAbsolute)
  int8_t bit = -1;            // a BOOL stored as one bit of the byte (located %IX/%QX)
  int8_t valueBit = -1;       // bit access w.3 into an integer (type is BOOL)
  TypeId bitHost = kNoType;   // the integer type holding valueBit
  const VarInfo* var = nullptr;  // the declared variable, when the place is one (for checks)
  bool constant = false;
  bool isInput = false;       // an input of a function (writable) or FB (writable inside only)
  // A REFERENCE TO standing for its referee: where the reference's own address slot is, for
  // REF= (rebinding) and __ISVALIDREF. Places derived from it (members, elements) clear it.
  bool viaReference = false;
  uint16_t referenceBase = kAbsolute;
  uint32_t referenceOffset = 0;
};

// The result of an expression.
struct Value {
  enum class Kind : uint8_t { Reg, Const, Addr, Void, Error };
  Kind kind = Kind::Error;
  TypeId type = kNoType;
  uint16_t reg = 0;
  ConstValue c;
  Place place;                // Kind::Addr: aggregates (strings, structs, arrays) by address
  bool untyped = false;       // an integer/real literal without a type prefix: adapts to context
  // Kind::Reg of an integer type: the low bits are right but the register is not yet sign- or
  // zero-extended from the IEC width (the result of + - * NOT). Stores and further + - *
  // AND OR XOR only need the low bits; toReg() extends it for everything else.
  bool wrapped = false;
  // ADR's result (and pointer arithmetic on it): an address CODESYS lets any POINTER TO take.
  bool untypedAddress = false;
  bool ok() const { return kind != Kind::Error; }
  static Value error() { return Value{}; }
};

class PouCompiler {
 public:
  struct Binding {
    size_t param = 0;           // index into the callee's parameter list
    Value value;                // inputs: the evaluated argument
    uint16_t address = 0xffff;  // in-outs: register holding the actual's address
    const CallArg* arg = nullptr;     // the argument as written (for outputs: the receiver)
  };
  PouCompiler(CompileContext& ctx, PouSym& pou);
  // Emits the POU's code into ctx.module.code and fills its PouInfo; returns false on errors.
  void compile();

  // --- shared helpers used by the expression, call and builtin parts ---
  Diagnostics& diags() { return ctx_.diags; }
  TypeTable& types() { return ctx_.types; }
  ProgramModel& model() { return ctx_.model; }

  uint16_t allocReg();
  uint16_t regMark() const { return nextReg_; }
  void freeRegs(uint16_t mark) { nextReg_ = mark; }
  uint32_t emit(bc::Op op, uint16_t a, uint16_t b, uint16_t c);
  uint32_t emitBx(bc::Op op, uint16_t a, uint32_t bx);
  uint32_t here() const;
  void patchJump(uint32_t at, uint32_t target);
  uint32_t emitJump(bc::Op op, uint16_t reg);  // returns index to patch
  void jumpTo(bc::Op op, uint16_t reg, uint32_t target);
  uint16_t loadConstInt(int64_t v, uint16_t into = 0xffff);
  uint16_t loadConstReal(double v);
  uint16_t indexDesc(const bc::IndexDesc& d);  // its index in module.indexes (shared by equal shapes)
  // Allocates `size` bytes of statement-scoped scratch in the frame; returns a place on fp.
  Place frameTemp(TypeId type);
  uint32_t stringLiteral(const std::string& bytes, bool wide = false);

  // Values
  Value expr(const Expr& e, TypeId expected = kNoType);
  uint16_t toReg(Value v);                       // a scalar value in a register
  // Like toReg, but a wrapped value stays wrapped: for consumers of the low bits only.
  uint16_t rawReg(const Value& v);
  Value wrappedValue(TypeId type, uint16_t reg);  // a Reg value marked wrapped when its width needs it
  // Converts a value to `to` (IEC conversion rules; constants fold); reports E202 if impossible.
  Value convert(Value v, TypeId to, SourceLocation loc);
  Value coerce(Value v, TypeId to, SourceLocation loc);  // implicit, with diagnostics
  uint16_t normalize(uint16_t reg, TypeId type);       // in place; returns reg
  uint16_t normalizedCopy(uint16_t reg, TypeId type);  // into a new register if it needs it
  uint16_t normalizeInto(uint16_t to, uint16_t reg, TypeId type);  // `to`, or reg if nothing to do
  Value regValue(TypeId type, uint16_t reg);
  // An integer (or BOOL, enum) constant that fits a signed 16-bit immediate; nullopt otherwise.
  static std::optional<int16_t> smallConst(const Value& v);
  Value constInt(TypeId type, int64_t v);

  // Places
  std::optional<Place> place(const Expr& e, bool forWrite);
  // The variable a bare name denotes (local, member, VAR_INST, global); nullopt, silently, if none.
  std::optional<Place> namePlace(const Expr& e, bool forWrite);
  uint16_t load(const Place& p);
  void store(const Place& p, uint16_t reg);
  // Stores a small integer constant with one STK_*; false (nothing emitted) if it cannot.
  bool storeConst(const Place& p, const Value& v);
  uint16_t addressOf(const Place& p);
  void assign(const Place& target, const Expr& source, SourceLocation loc);
  void assignValue(const Place& target, Value v, SourceLocation loc);
  void copyBytes(uint16_t dstAddr, uint16_t srcAddr, uint32_t size);

  // Calls (codegen_call.cpp)
  Value call(const Expr& e, TypeId expected);
  struct Receiver {
    uint16_t thisReg = kThis;
    PouSym* staticClass = nullptr;       // FB type of the receiver (null for interfaces)
    InterfaceSym* viaInterface = nullptr;
    bool exact = false;                  // a value instance or SUPER^: no dynamic dispatch
  };
  Value propertyGet(const PropertySym& prop, const Receiver& recv, SourceLocation loc);
  // `x.P` where P is a property of x's FB or interface type: the getter's value; nullopt if not a property.
  std::optional<Value> memberProperty(const Expr& e);
  // `x.P := v` / `P := v` as a property write; false if the target is not a property.
  bool propertySet(const Expr& target, const Expr& value, SourceLocation loc);
  // Standard functions (codegen_builtin.cpp, builtin_*.cpp); nullopt if `name` is not one.
  std::optional<Value> builtin(const std::string& upperName, const Expr& e, TypeId expected);
  // CODESYS operators (codegen_operators.cpp); nullopt if `name` is not one of them.
  std::optional<Value> codesysOperator(const std::string& upperName, const Expr& e);
  Value callNative(bc::Native n, const std::vector<uint16_t>& argRegs, TypeId resultType);
  Value stringResult(bc::Native n, std::vector<uint16_t> args, TypeId stringType);
  Value compare(const Expr& e, Value a, Value b);
  Value arithmetic(const Expr& e, Value a, Value b);

  PouSym& pou() { return pou_; }
  CompileContext& ctx() { return ctx_; }

 private:
  // Statements (codegen_stmt.cpp)
  void edgeInputs();
  void statements(const StmtList& list);
  void statement(const Stmt& s);
  void assignment(const Stmt& s);
  void ifStatement(const Stmt& s);
  void caseStatement(const Stmt& s);
  void forStatement(const Stmt& s);
  void whileStatement(const Stmt& s);
  void repeatStatement(const Stmt& s);
  void jumpOut(const Stmt& s);
  uint16_t condition(const Expr& e);

  // JMP and labels (codegen_jump.cpp)
  void collectLabels(const StmtList& list);
  bool openLabelScope(const StmtList& list);
  void closeLabelScope();
  void placeLabel(const Stmt& s);
  void jump(const Stmt& s);

  // Coverage probes (codegen_coverage.cpp), emitted only while covering_.
  bool coversPou() const;
  void probe(CoverageKind kind, SourceLocation loc, uint16_t arm = 0, uint16_t arms = 0, std::string name = {});
  void coverStatement(const Stmt& s);
  // The number of arms of IF/CASE `s` whose entries are probed (implicit ELSE included), 0 if none are.
  uint16_t probedArms(const Stmt& s, size_t explicitArms) const;

  // Expressions (codegen_expr.cpp)
  Value literal(const Expr& e, TypeId expected);
  Value unary(const Expr& e, TypeId expected);
  Value binary(const Expr& e, TypeId expected);
  Value shortCircuit(const Expr& e);
  Value dateArithmetic(const Expr& e, Value a, Value b);
  Value pointerArithmetic(const Expr& e, Value a, Value b);
  Value pointerDistance(Value a, Value b);
  std::optional<Place> memberPlace(const Expr& e, bool forWrite);
  std::optional<Place> indexPlace(const Expr& e, bool forWrite);
  std::optional<Place> valuePlace(const Value& v);
  std::optional<Place> pointerIndexPlace(const Place& pointer, const Expr& index);
  std::optional<Place> stringIndexPlace(const Place& string, const Expr& index);
  // Byte offset of an indexed element: folded constant part plus a register (kNoReg: none).
  struct CheckedOffset {
    int64_t constant = 0;
    uint16_t variable = kNoReg;
  };
  bool addCheckedIndex(const Expr& index, const bc::ArrayDim& dim, uint64_t stride, const std::string& what,
                       CheckedOffset& offset);
  Place offsetPlace(Place p, const CheckedOffset& offset);
  std::optional<Place> derefPlace(const Expr& e);
  Place varPlace(const VarInfo& v, uint16_t instanceBase);
  Place referee(const Place& referenceSlot);
  static Place referenceSlot(const Place& referee);  // the reverse, for a place with viaReference

  std::vector<const VarInfo*> fbParams(PouSym& fb);
 public:
  // VAR_IN_OUT and REFERENCE TO inputs receive the address of the actual variable.
  bool passesAddress(const VarInfo& p);
 private:
  void evaluateInputs(const std::vector<const VarInfo*>& params, std::vector<Binding>& bindings);
  // ENTER for `callee` and its `this` (0xffff: none); returns the callee's window register.
  uint16_t emitFrameCall(PouSym& callee, uint16_t thisReg);
  // Copies the outputs connected with `=>` from the callee's frame or instance at `base`.
  void readOutputs(uint16_t base, const std::vector<Binding>& bindings, const std::vector<const VarInfo*>& params);
  Value returnValue(PouSym& callee, uint16_t frameReg);
  Value callFunction(PouSym& fn, const Expr& e);
  Value libraryCall(const std::string& upperName, const Expr& e, TypeId expected);
  Value callFbInstance(const Place& inst, PouSym& fb, const Expr& e);
  Value callMethod(const std::string& name, const Receiver& recv, const Expr& e);
  Value callAction(PouSym& action, uint16_t thisReg);
  std::vector<std::pair<uint32_t, PouSym*>> dispatchTargets(const Receiver& recv, const std::string& upperName, bool property, bool setter);
  bool receiverOf(const Expr& objectExpr, Receiver& recv);
  // The declared type of a bare name or THIS^/SUPER^ without generating code; kNoType otherwise.
  TypeId staticTypeOf(const Expr& object);
  TypeId staticMemberType(const Expr& member);  // staticTypeOf of `a.b`
  bool hasProperty(TypeId type, const std::string& upperName);  // an FB or interface type's

  // CODESYS operators (codegen_operators.cpp)
  struct InstanceOperand {
    uint16_t address = 0;      // register holding the instance's address (0 for a null interface)
    const PouSym* fb = nullptr;  // the FB type when the operand is an instance, null for interfaces
  };
  std::optional<std::vector<const Expr*>> operatorOperands(const Expr& e, size_t count);
  std::optional<InstanceOperand> instanceOperand(const Expr& operand, const std::string& op);
  Value isValidRef(const Expr& e);
  Value queryInterface(const Expr& e);
  Value queryPointer(const Expr& e);
  // Compares the class id at `address` with classIds: {found (BOOL), address or 0}.
  std::pair<uint16_t, uint16_t> classTest(uint16_t address, const std::vector<uint32_t>& classIds);
  std::optional<InstanceOperand> attemptSource(const Expr& operand);
  void attemptAssignment(const Stmt& s);
  Value memoryFunction(const std::string& upperName, const Expr& e);

  struct Loop {
    std::vector<uint32_t> breaks;
    std::vector<uint32_t> continues;
  };
  // A label of the statement list being compiled: its address once reached, and the forward
  // jumps waiting for it.
  struct JumpLabel {
    const Stmt* stmt = nullptr;
    std::optional<uint32_t> target;
    std::vector<uint32_t> pending;
  };
  using LabelScope = std::vector<JumpLabel>;

  CompileContext& ctx_;
  PouSym& pou_;
  uint32_t codeStart_ = 0;
  uint16_t nextReg_ = 2;
  uint16_t maxReg_ = 2;
  uint16_t regTop_ = 2;  // one past the highest register allocated by the statement being compiled
  uint32_t tempTop_ = 0;
  uint32_t tempMax_ = 0;
  std::vector<Loop> loops_;
  std::vector<const Stmt*> bodyLabels_;     // every label of the body, for E219/E220
  std::vector<LabelScope> labelScopes_;     // the labels of each enclosing statement list
  std::vector<uint32_t> returns_;
  bool covering_ = false;
};

// Helpers shared by the codegen files.
bc::Native wideNative(bc::Native narrow);  // STR_x -> WSTR_x
bc::Op loadOp(ElemType e);
bc::Op loadAbsOp(ElemType e);
bc::Op storeOp(ElemType e);
bc::Op storeAbsOp(ElemType e);
std::string describe(const TypeTable& types, TypeId t);

}  // namespace virtcom::st
