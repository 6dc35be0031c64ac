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

std::unique_ptr<WriteAudit> makeWriteAudit(AuditLevel level, std::unique_ptr<AuditedNames> names, std::ostream& log,
                                                WriteAudit::Sink record) {
  if (level == AuditLevel::Off) return nullptr;
  const bool each = level == AuditLevel::Each;
  WriteAudit::Sink sink;
  if (each || record)
    sink = [&log, each, record = std::move(record)](const WriteRecord& r) {
      if (each) log << "audit: " << formatWriteRecordWithTimes(r) << "\n";
      if (record) record(r);
    };
  return std::make_unique<WriteAudit>(std::move(names), std::move(sink));
}

WriteAudit::Sink intoTrace(const std::unique_ptr<cell::Cell>& cell, WriteAudit::Sink next) {
  return [&cell, next = std::move(next)](const WriteRecord& r) {
    cell->trace.keepExternalWrite(r);
    if (next) next(r);
  };
}

std::string auditSummary(std::initializer_list<const WriteAudit*> audits) {
  std::array<uint64_t, kWriteProtocolCount> counts{};
  for (const WriteAudit* audit : audits)
    if (audit)
      for (size_t p = 0; p < kWriteProtocolCount; ++p) counts[p] += audit->count(static_cast<WriteProtocol>(p));
  return "audit: " + externalWritesText(counts);
}

}  // namespace virtcom::cli
