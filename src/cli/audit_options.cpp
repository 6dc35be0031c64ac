#include "cli/audit_options.hpp"

#include <map>

namespace virtcom::cli {

void addAuditOption(CLI::App* cmd, AuditLevel& level) {
  const std::map<std::string, AuditLevel> levels{{"off", AuditLevel::Off}, {"summary", AuditLevel::Summary}, {"each", AuditLevel::Each}};
  cmd->add_option("--audit-writes", level,
                  "audit of writes from ADS, Modbus and OPC UA clients on stderr: off, summary (default: the count per protocol "
                  "at the end) or each (also a line per write: times, protocol, peer, variable, old -> new value; docs/security.md)")
      ->transform(CLI::CheckedTransformer(levels, CLI::ignore_case));
}

std::unique_ptr<plc::WriteAudit> makeWriteAudit(AuditLevel level, const bc::Module& module, std::ostream& log) {
  if (level == AuditLevel::Off) return nullptr;
  plc::WriteAudit::Sink sink;
  if (level == AuditLevel::Each) sink = [&log](const plc::WriteRecord& r) { log << "audit: " << plc::formatWriteRecordWithTimes(r) << "\n"; };
  return std::make_unique<plc::WriteAudit>(module, std::move(sink));
}

std::string auditSummary(const plc::WriteAudit& audit) {
  std::string out = "audit: " + std::to_string(audit.total()) + " external writes (";
  for (size_t p = 0; p < kWriteProtocolCount; ++p) {
    const auto protocol = static_cast<WriteProtocol>(p);
    out += (p ? ", " : "") + std::string(writeProtocolName(protocol)) + " " + std::to_string(audit.count(protocol));
  }
  return out + ")";
}

}  // namespace virtcom::cli
