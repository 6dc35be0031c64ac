#pragma once
// `--audit-writes off|summary|each` on the commands that serve the PLC (docs/security.md, Audit
// of external writes): one WriteAudit for every server of the command, its records on
// stderr and its count per protocol at the end of the run.
#include <initializer_list>
#include <memory>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "cell/cell.hpp"
#include "core/write_audit.hpp"

namespace virtcom::cli {

enum class AuditLevel { Off, Summary, Each };

void addAuditOption(CLI::App* cmd, AuditLevel& level);

// The audit the servers' queues report to (nullptr when --audit-writes off), logging each record
// to `log` ("audit: 0.120s 2026-12-02T15:40:01.123Z modbus 127.0.0.1:50123 MAIN.speed (%MW0): 0 -> 5")
// at level Each, and handing each to `record` (if set: the historian) at every level but Off.
std::unique_ptr<WriteAudit> makeWriteAudit(AuditLevel level, std::unique_ptr<AuditedNames> names, std::ostream& log,
                                                WriteAudit::Sink record = {});

// Each record into the trace of the cell in use (Trace::keepExternalWrite: the reports' counts and
// table of writes; a reset from the HMI replaces the cell, and its new run counts from 0), then
// to `next` (if set: the historian). Called on the scan thread, which owns the trace.
WriteAudit::Sink intoTrace(const std::unique_ptr<cell::Cell>& cell, WriteAudit::Sink next);

// "audit: 3 external writes (ads 1, modbus 2, opcua 0, http 0)" (also with none: the run saw none),
// the counts of every audit given (null ones skipped: a command may audit more than one image).
std::string auditSummary(std::initializer_list<const WriteAudit*> audits);

}  // namespace virtcom::cli
