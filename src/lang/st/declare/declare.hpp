#pragma once
// The declaration pass: turns the parsed files into a ProgramModel — named types with their
// layouts, POUs with their variables, globals, tasks — and writes the initial memory image.
// It reports every declaration error; code generation runs only if it found none.
#include <map>
#include <optional>
#include <set>

#include "core/diagnostics.hpp"
#include "lang/st/declare/const_eval.hpp"
#include "lang/st/declare/image_builder.hpp"
#include "lang/st/declare/program_model.hpp"

namespace virtcom::st {

class Declarer {
 public:
  Declarer(const std::vector<CompilationUnit>& units, Diagnostics& diags, TypeTable& types, ProgramModel& model,
           ImageBuilder& image, bc::Module& module);

  // Runs every declaration step; afterwards the model is complete and the image holds the
  // initial values of globals and program instances.
  void run();

  // Resolves a written type in the scope of `pou` (may be null). Reports and returns kNoType on error.
  TypeId resolveType(const TypeSpec& spec, const PouSym* pou);
  ConstContext constContext(const PouSym* pou);
  std::optional<ConstValue> constant(const Expr& e, const PouSym* pou, bool quiet = false);
  // Writes the default value of `type` (then `init`, if given) into `dst` (type size bytes).
  void writeInitial(TypeId type, uint8_t* dst, const Expr* init, const PouSym* pou);
  // Converts a constant to the representation of a scalar type and writes it (width of the type).
  void writeScalar(TypeId type, uint8_t* dst, const ConstValue& v, int8_t bit);
  // Looks up an enum value by type name and value name.
  std::optional<ConstValue> enumValue(const std::string& type, const std::string& value);
  // Looks up a bare enumerator name (unique across all enums); sets `type`.
  std::optional<ConstValue> bareEnumerator(const std::string& name, TypeId& type);
  // Checks that a constant fits the integer type; reports E117 at `loc` otherwise.
  bool checkRange(TypeId type, const ConstValue& v, SourceLocation loc);

 private:
  void registerNames();
  void registerQueryInterface();
  // Reports variables that cannot exist: instances of ABSTRACT FBs, names of standard functions.
  void checkVariable(const VarInfo& v);
  void allocateProcessAreas();
  // Global CONSTANTs are needed (array bounds, string lengths) before globals are laid out.
  void collectGlobalConstants();
  void registerPou(const Pou& pou, uint32_t fileId);
  void declareTypes();
  void fillTypeDecl(const TypeDecl& decl, TypeId id);
  void fillEnum(TypeId id, const TypeSpec& spec, const PouSym* pou);
  TypeId resolveNamed(const TypeSpec& spec, const PouSym* pou);
  void layoutStruct(TypeId id, const std::vector<VarDecl>& fields, const std::string& base, bool isUnion,
                    SourceLocation loc);
  bool overlayable(TypeId type) const;  // may share its bytes with another UNION member
  void declarePous();
  void layoutInstance(PouSym& pou);
  bool layoutFbOf(const TypeSpec& spec, VarSection section);
  void layoutFrame(PouSym& pou);
  void addMembers(PouSym& pou, const Pou& ast, bool methodInst);
  bool edgeAllowed(const PouSym& pou, const VarBlock& block, const VarDecl& decl) const;
  void checkEdgeDeclarations(const PouSym& pou);  // E108 for R_EDGE/F_EDGE where they cannot be
  void addEdgeState(PouSym& pou, size_t inputIndex);
  void declareMethods(PouSym& owner);
  void linkInheritance();
  void declareInterfaces();
  void declareGlobals();
  // VAR_EXTERNAL only refers to a global: it must exist with the same type and CONSTANT-ness.
  void checkExternals();
  void declareConfiguration();

 public:
  // Writes each POU's frame template (initial values of its locals, zeros for the temporaries
  // code generation added) into the image. Call after code generation has fixed frame sizes.
  void buildTemplates();

 private:
  void placeLocated(VarInfo& v, const std::string& address);
  uint32_t locatedSizeEstimate(const TypeSpec& t);
  const std::vector<uint8_t>& defaultBytes(TypeId type);
  void applyInit(TypeId type, uint8_t* dst, const Expr& init, const PouSym* pou);
  void applyMemberInits(TypeId type, uint8_t* dst, const std::vector<CallArg>& args, const PouSym* pou);
  // `inst : FB_T(a := 1)`: without a METHOD FB_init the arguments initialise the named members;
  // with one they are FB_init's arguments (see buildInitProgram).
  void applyDeclarationArgs(TypeId type, uint8_t* dst, const VarDecl& decl, const PouSym* pou);
  std::optional<ConstValue> lookupConstName(const Expr& e, const PouSym* pou);
  std::optional<ConstValue> declaredConstant(const Pou& ast, const std::string& upperName, const PouSym* pou);

  const std::vector<CompilationUnit>& units_;
  Diagnostics& diags_;
  TypeTable& types_;
  ProgramModel& model_;
  ImageBuilder& image_;
  bc::Module& module_;
  std::map<std::string, const TypeDecl*> typeDecls_;      // upper-cased
  std::set<std::string> resolving_;                        // cycle detection for types
  std::set<const PouSym*> layingOut_;                      // cycle detection for FB instances
  std::set<const PouSym*> laidOut_;                        // FB/PROGRAM instances with their layout done
  std::set<TypeId> defaultsInProgress_;                    // cycle guard for defaultBytes
  std::map<TypeId, std::vector<std::pair<size_t, const Expr*>>> fieldInits_;  // struct field inits
  std::map<TypeId, const Expr*> typeInits_;                // TYPE x : T := init
  std::map<TypeId, std::vector<uint8_t>> defaults_;
  std::map<std::string, std::vector<std::pair<TypeId, int64_t>>> enumerators_;  // upper name -> (enum, value)
  std::map<std::string, ConstValue> globalConstants_;  // "X" and "GVL.X"
  std::set<std::string> constantsInProgress_;           // cycle guard for declaredConstant
  uint32_t nextClassId_ = 1;
  bool layoutStarted_ = false;
};

// A VarInfo for one declared name (section, flags and attributes filled in; no storage yet).
VarInfo makeVar(const DeclName& n, const VarDecl& decl, TypeId type, VarSection section, const VarBlock& block);

// Parses %IX1.2 / %QW4 / %MD2 into (area I/Q/M, byte offset, bit or -1, size in bytes).
struct DirectAddress {
  char area = 'I';
  uint32_t byteOffset = 0;
  int8_t bit = -1;
  uint32_t size = 1;
};
std::optional<DirectAddress> parseDirectAddress(std::string_view text);
// Why parseDirectAddress refused `text`, for E109: a hierarchical address (%MW1.7.9, %IX0.0.1)
// is named as such, anything else is malformed.
std::string directAddressError(std::string_view text);

}  // namespace virtcom::st
