#include "report/html_writes.hpp"

#include <numeric>

#include "report/text_util.hpp"

namespace virtcom::report {

namespace {

std::string writeRow(const WriteRecord& r) {
  return "<tr><td>" + formatSeconds(r.virtualNs, 3) + "</td><td class=\"l\">" + utcTimeText(r.wallNs) + "</td><td class=\"l\">" +
         std::string(writeProtocolName(r.writer.protocol)) + "</td><td class=\"l\">" + escapeHtml(writerPeer(r.writer)) +
         "</td><td class=\"l\">" + escapeHtml(writtenVariableText(r)) + "</td><td class=\"l wrap\">" + escapeHtml(r.oldValue) +
         " \u2192 " + escapeHtml(r.newValue) + (r.writer.force ? " (forced)" : "") + "</td></tr>\n";
}

}  // namespace

std::string externalWritesHtml(const Trace& trace) {
  if (!trace.writesAudited) return {};
  std::string out = "<section class=\"panel\" id=\"writes\"><h2>" + externalWritesText(trace.externalWrites) +
                    "<span class=\"hint\">clients' writes into the soft PLC, in the order they landed</span></h2>\n";
  if (trace.writeRecords.empty()) return out + "<p class=\"note\">No client wrote into the PLC during this run.</p></section>\n";
  out += "<table class=\"events\"><thead><tr><th>Time s</th><th class=\"l\">Wall time (UTC)</th><th class=\"l\">Protocol</th>"
         "<th class=\"l\">Peer</th><th class=\"l\">Variable</th><th class=\"l\">Old \u2192 new</th></tr></thead><tbody>\n";
  for (const WriteRecord& r : trace.writeRecords) out += writeRow(r);
  out += "</tbody></table>\n";
  // Only the first records are kept (Trace::kKeptWriteRecords): the file stays small when a
  // client wrote every scan.
  const uint64_t total = std::accumulate(trace.externalWrites.begin(), trace.externalWrites.end(), uint64_t{0});
  if (total > trace.writeRecords.size())
    out += "<p class=\"note\">" + std::to_string(total - trace.writeRecords.size()) + " more not shown: the report lists the first " +
           std::to_string(trace.writeRecords.size()) + ".</p>\n";
  return out + "</section>\n";
}

}  // namespace virtcom::report
