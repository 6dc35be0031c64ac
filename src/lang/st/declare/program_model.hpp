#pragma once
// What the declaration pass learns about a program: every POU with its variables and layout,
// global variables, named types and tasks. Code generation reads it; it never edits the AST.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/ascii.hpp"
#include "lang/syntax/ast.hpp"
#include "lang/st/declare/type_table.hpp"

namespace virtcom::st {

// Upper-cased name: the key of every case-insensitive lookup.
inline std::string upper(std::string_view name) { return asciiUpper(name); }

// The generated PROGRAM that runs a configured program instance with its arguments
// (`PROGRAM p WITH t : P(in := g, out => h)`): it calls `p` as `p(in := g, out => h)`, so inputs
// are copied in before every call and outputs out after it. The task runs it in place of `p`.
std::string configCallerName(std::string_view instanceName);

enum class Storage : uint8_t {
  Absolute,  // address is a memory address (globals, located variables, program members)
  Instance,  // offset from `this` (FB/method/program members reached through an instance)
  Frame,     // offset from fp (function and method locals, VAR_TEMP, inputs of functions)
};

struct ConstValue {
  enum class Kind : uint8_t { None, Int, Real, String };
  Kind kind = Kind::None;
  int64_t i = 0;     // also unsigned values (two's complement) and TIME/DATE raw values
  double f = 0;
  std::string s;
  TypeId type = kNoType;  // the type it was written as, when known (typed literals, constants)
};

struct VarInfo {
  std::string name;             // as declared
  SourceLocation loc;
  TypeId type = kNoType;
  VarSection section = VarSection::Var;
  Storage storage = Storage::Frame;
  uint32_t offset = 0;          // address (Absolute) or offset (Instance/Frame)
  int8_t bit = -1;              // located BOOL packed into a bit
  bool constant = false;
  bool byReference = false;     // VAR_IN_OUT: the slot holds an 8-byte address of the actual
  bool readOnly = false;        // {attribute 'ads_readonly'}
  bool hidden = false;          // internal state of a library FB
  bool retain = false;          // declared in a RETAIN or PERSISTENT block
  const VarDecl* decl = nullptr;
  // An R_EDGE/F_EDGE input: members[edgeMember] is the hidden BOOL the POU's own code reads
  // in its place (the edge of this call), members[edgeMember + 1] the input's previous value.
  EdgeKind edge = EdgeKind::None;
  uint32_t edgeMember = 0;
  ConstValue constValue;        // CONSTANT of a scalar type: the folded value (kind != None)
};

struct PouSym;

struct MethodRef {
  PouSym* method = nullptr;     // the implementation visible in this class (own or inherited)
};

struct PropertySym {
  std::string name;
  TypeId type = kNoType;
  PouSym* getter = nullptr;
  PouSym* setter = nullptr;
  SourceLocation loc;
};

struct PouSym {
  PouKind kind = PouKind::Program;
  std::string name;                 // as declared ("Start" for a method)
  std::string qualifiedName;        // "FB_Motor.Start"
  const Pou* ast = nullptr;
  uint32_t fileId = 0;
  PouSym* owner = nullptr;          // methods, actions, accessors: the FB/PROGRAM they belong to
  PouSym* base = nullptr;           // EXTENDS
  std::vector<std::string> interfaces;  // IMPLEMENTS, upper-cased
  bool isAbstract = false;
  bool isLibrary = false;           // from the built-in prelude (standard FBs)
  bool isInterfaceMethod = false;   // prototype inside an INTERFACE

  // Instance (FB/PROGRAM): members in declaration order, base members first.
  TypeId instanceType = kNoType;
  bool hasClassHeader = false;      // first 4 bytes of the instance hold the class id
  uint32_t classId = 0;
  std::vector<VarInfo> members;     // Instance storage
  std::map<std::string, size_t> memberIndex;  // upper-cased name -> members index

  // Frame (every POU): inputs of functions/methods, locals, temps, return value.
  std::vector<VarInfo> locals;      // Frame storage
  std::map<std::string, size_t> localIndex;
  uint32_t frameSize = 0;
  uint32_t frameTemplate = 0;       // address of the frame's initial bytes in the static image
  TypeId returnType = kNoType;      // functions, methods, property getters
  uint32_t returnOffset = 0;        // in the frame
  std::vector<const VarInfo*> params;  // formal parameters in declaration order (inputs, in_outs, outputs)

  std::map<std::string, PouSym*> methods;      // upper-cased -> own or inherited implementation
  std::map<std::string, PropertySym> properties;
  std::map<std::string, PouSym*> actions;

  uint32_t bcIndex = 0;             // index in Module::pous
  bool compiled = false;
  bool onCallStack = false;         // recursion check
  std::vector<PouSym*> callees;     // for the recursion check
};

struct InterfaceSym {
  std::string name;
  const Interface* ast = nullptr;
  std::vector<std::string> bases;   // upper-cased
  std::map<std::string, PouSym*> methods;   // prototypes
  std::map<std::string, PropertySym> properties;
  TypeId type = kNoType;            // an interface-typed variable: 8-byte reference
};

struct GlobalVar {
  VarInfo var;
  std::string listName;             // GVL name ("" if none)
};

struct TaskSym {
  std::string name;
  int64_t intervalNs = 10'000'000;
  int32_t priority = 0;
  std::vector<std::string> programInstances;  // upper-cased instance names in order
  // Created by the compiler, not declared by a TASK: `MainTask` without a CONFIGURATION,
  // `__DEFAULT` for configured programs without WITH. A cycle time the user gives outside the
  // program (`--cycle-time`, `plc.cycle_time`) applies to it; declared tasks keep their INTERVAL.
  bool isDefault = false;
};

struct ProgramInstanceSym {
  std::string name;
  PouSym* pou = nullptr;
  uint32_t address = 0;
};

struct ProgramModel {
  std::vector<std::unique_ptr<PouSym>> pous;       // all, including methods/actions/accessors
  std::map<std::string, PouSym*> pouByName;        // upper-cased top-level POUs
  std::map<std::string, InterfaceSym> interfaces;
  std::map<std::string, TypeId> namedTypes;        // upper-cased TYPE names (and FB instance types)
  std::map<TypeId, PouSym*> fbByType;              // instance type -> FB/PROGRAM
  std::map<TypeId, InterfaceSym*> interfaceByType;
  std::map<TypeId, std::pair<int64_t, int64_t>> subranges;  // subrange alias -> bounds
  std::vector<GlobalVar> globals;
  std::map<std::string, size_t> globalIndex;       // "X" and "GVL.X" -> globals index
  std::vector<std::string> globalListNames;        // upper-cased GVL names
  std::vector<TaskSym> tasks;
  std::vector<ProgramInstanceSym> programInstances;
  std::vector<PouSym*> classes;                    // FBs with a class header, by class id - 1
};

}  // namespace virtcom::st
