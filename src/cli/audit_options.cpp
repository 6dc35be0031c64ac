#include "cli/audit_options.hpp"

#include <array>
#include <map>

namespace virtcom::cli {

void addAuditOption(CLI::App* cmd, AuditLevel& level) {
  const std::map<std::string, AuditLevel> levels{{"off", AuditLevel::Off}, {"summary", AuditLevel::Summary}, {"each", AuditLevel::Each}};
  cmd->add_option("--audit-writes", level,
                  "audit of writes from ADS, Modbus, OPC UA and HMI (HTTP) clients on stderr: off, summary (default: the count per protocol "
                  "at the end) or each (also a line per write: times, protocol, peer, variable, old -> new value; docs/security.md)")
      ->transform(CLI::CheckedTransformer(levels, CLI::ignore_case));
}

std::unique_ptr<plc::WriteAudit> makeWriteAudit(AuditLevel level, const bc::Module& module, std::ostream& log,
                                                plc::WriteAudit::Sink record) {
  if (level == AuditLevel::Off) return nullptr;
  const bool each = level == AuditLevel::Each;
  plc::WriteAudit::Sink sink;
  if (each || record)
    sink = [&log, each, record = std::move(record)](const WriteRecord& r) {
      if (each) log << "audit: " << plc::formatWriteRecordWithTimes(r) << "\n";
      if (record) record(r);
    };
  return std::make_unique<plc::WriteAudit>(module, std::move(sink));
}

plc::WriteAudit::Sink intoTrace(const std::unique_ptr<cell::Cell>& cell, plc::WriteAudit::Sink next) {
  return [&cell, next = std::move(next)](const WriteRecord& r) {
    cell->trace.keepExternalWrite(r);
    if (next) next(r);
  };
}

std::string auditSummary(const plc::WriteAudit& audit) {
  std::array<uint64_t, kWriteProtocolCount> counts{};
  for (size_t p = 0; p < kWriteProtocolCount; ++p) counts[p] = audit.count(static_cast<WriteProtocol>(p));
  return "audit: " + externalWritesText(counts);
}

}  // namespace virtcom::cli
