#pragma once
// What the soft PLC's data area names for the write audit (core/write_audit.hpp): its declared
// variables (globals, program variables; a write narrowed to the struct member or array element
// it changed), their values formatted as the PLC's types say and their IEC addresses
// ("%QX0.3", "%MW4") for located ones.
#include <memory>

#include "bytecode/module.hpp"
#include "core/write_audit.hpp"

namespace virtcom::plc {

// `module` must outlive the names.
std::unique_ptr<AuditedNames> auditedVariables(const bc::Module& module);

}  // namespace virtcom::plc
