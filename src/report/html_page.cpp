#include "report/html_page.hpp"

#include "report/text_util.hpp"

namespace virtcom::report {

namespace {

constexpr const char* kCss = R"css(
:root{--fg:#1f2328;--muted:#59636e;--line:#d1d9e0;--soft:#eef1f4;--bg:#f6f8fa;--accent:#2563eb;--err:#d7263d;--fault:#e07b00;--ok:#1a7f37;--warn:#9a6700}
*{box-sizing:border-box}
body{margin:0;background:var(--bg);color:var(--fg);font:14px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,"Helvetica Neue","DejaVu Sans",Arial,sans-serif}
main{max-width:1290px;margin:0 auto;padding:22px 26px 34px}
header{display:flex;align-items:center;gap:14px;flex-wrap:wrap;margin-bottom:4px}
h1{font-size:24px;margin:0;font-weight:650;letter-spacing:-.01em}
.subtitle{color:var(--muted);margin:0 0 16px}
.pill{font-size:12px;font-weight:600;padding:2px 10px;border-radius:999px;border:1px solid}
.pill.ok{color:var(--ok);background:#dafbe1;border-color:#aceebb}
.pill.warn{color:var(--warn);background:#fff8c5;border-color:#eed888}
.pill.bad{color:var(--err);background:#ffebe9;border-color:#ffcecb}
.cards{display:grid;grid-template-columns:repeat(auto-fit,minmax(160px,1fr));gap:12px;margin-bottom:16px}
.card{background:#fff;border:1px solid var(--line);border-radius:8px;padding:11px 14px}
.card .k{font-size:11.5px;color:var(--muted);text-transform:uppercase;letter-spacing:.05em;font-weight:600}
.card .v{font-size:25px;font-weight:650;font-variant-numeric:tabular-nums;line-height:1.25;margin-top:2px}
.card .v small{font-size:14px;font-weight:500;color:var(--muted);margin-left:3px}
.card .d{font-size:12px;color:var(--muted)}
.card.bad{border-color:#ffcecb;background:#fffafa}
.card.bad .v{color:var(--err)}
.panel{background:#fff;border:1px solid var(--line);border-radius:8px;padding:14px 16px;margin-bottom:16px;overflow-x:auto}
h2{font-size:15px;margin:0 0 10px;font-weight:650}
h3{font-size:12.5px;margin:12px 0 4px;font-weight:650;color:var(--muted)}
h2 .hint{font-weight:400;color:var(--muted);font-size:12.5px;margin-left:8px}
svg.chart{display:block;max-width:100%;height:auto}
svg text{font-family:system-ui,-apple-system,"Segoe UI",Roboto,"Helvetica Neue","DejaVu Sans",Arial,sans-serif;font-size:11px;fill:var(--fg)}
svg .lane{font-size:12px;font-weight:600}
svg .group{font-size:10.5px;font-weight:700;letter-spacing:.08em;text-transform:uppercase;fill:var(--muted)}
svg .group-rule{stroke:var(--line)}
svg .zebra{fill:#f6f8fa}
svg .grid line{stroke:#e3e7eb}
svg .axis line{stroke:#8c959f}
svg .axis text{fill:var(--muted)}
svg .axis-title{font-style:italic}
svg .cycle rect{fill:var(--accent);fill-opacity:.06}
svg .cycle line{stroke:var(--accent);stroke-dasharray:4 3;stroke-opacity:.7}
svg .cycle-bracket line{stroke:var(--accent);stroke-width:1.4}
svg .cycle-bracket rect{fill:#fff}
svg .cycle-bracket text{fill:var(--accent);font-weight:650}
svg .bar{stroke:#fff;stroke-width:.6}
svg .bar:hover{stroke:#1f2328;stroke-width:1.4}
svg .bar.err{stroke:var(--err);stroke-width:2.4}
svg .bar.run{fill-opacity:.5;stroke:#59636e;stroke-dasharray:3 2}
svg .bar-label{font-size:10.5px;font-weight:500;pointer-events:none}
svg line.collision{stroke:var(--err);stroke-width:1.6}
svg .collision-label{fill:var(--err);font-weight:650}
svg .collision-dot{fill:var(--err);stroke:#fff;stroke-width:1.5}
svg line.fault{stroke:var(--fault);stroke-width:1.5;stroke-dasharray:5 3}
svg .fault-label{fill:var(--fault);font-weight:650}
svg .fault-dot{fill:var(--fault);stroke:#fff;stroke-width:1.2}
svg .wave{fill:none;stroke:var(--accent);stroke-width:1.5;stroke-linejoin:round}
svg .area{fill:var(--accent);fill-opacity:.1}
svg .wave.bool{stroke:var(--ok)}
svg .area.bool{fill:var(--ok);fill-opacity:.13}
svg .range,svg .sub{fill:var(--muted);font-size:10px}
svg .ebar{fill:#4e79a7}
svg .evalue{font-variant-numeric:tabular-nums;font-weight:600}
.legend{list-style:none;display:flex;flex-wrap:wrap;gap:6px 18px;margin:10px 0 0;padding:10px 0 0;border-top:1px solid var(--soft);font-size:12.5px}
.legend li{display:flex;align-items:center;gap:6px}
.legend .sep{width:1px;height:16px;background:var(--line)}
.sw{width:16px;height:12px;border-radius:2px;display:inline-block;flex:none}
.sw.err{background:#fff;border:2px solid var(--err)}
.sw.run{background:#e8ecf0;border:1px dashed #59636e}
.sw.col{width:3px;height:16px;background:var(--err);border-radius:0}
.sw.flt{width:0;height:16px;border-left:2px dashed var(--fault);border-radius:0}
.sw.cyc{background:rgba(37,99,235,.1);border-left:1px dashed var(--accent);border-right:1px dashed var(--accent);border-radius:0}
table{border-collapse:collapse;width:100%;font-variant-numeric:tabular-nums;font-size:13px}
th,td{padding:6px 10px;border-bottom:1px solid var(--soft);text-align:right;white-space:nowrap}
th{font-size:11.5px;color:var(--muted);font-weight:600;text-transform:uppercase;letter-spacing:.04em}
tr.total td{font-weight:650;border-top:1px solid var(--line);border-bottom:none}
.l{text-align:left}
td.bad{color:var(--err);font-weight:650}
td.wrap{white-space:normal}
table.events td:first-child,table.events th:first-child{width:90px}
table.events td:nth-child(2),table.events td:nth-child(3){width:1%}
.tag{font-size:11.5px;font-weight:650;padding:1px 8px;border-radius:999px}
.tag.col{color:var(--err);background:#ffebe9}
.tag.flt{color:var(--fault);background:#fff1e0}
.util{display:flex;align-items:center;gap:8px;justify-content:flex-end}
.track{width:96px;height:8px;background:var(--soft);border-radius:4px;overflow:hidden}
.fill{height:100%;background:var(--accent);border-radius:4px}
.note{color:var(--muted);font-size:12.5px;margin:8px 0 0}
.scroll{max-height:320px;overflow-y:auto}
.two{display:flex;flex-wrap:wrap;gap:0 16px}
.two .devices{flex:1 1 auto}
.two .energy{flex:1 1 480px}
footer{color:var(--muted);font-size:12px;margin-top:6px}
td.code{font-family:ui-monospace,"DejaVu Sans Mono",monospace;font-size:12.5px;text-align:left;white-space:normal}
td.muted{color:var(--muted)}
table.rules th:first-child,table.rules td:first-child{width:1%}
@media print{body{background:#fff}.panel,.card{break-inside:avoid}}
)css";

}  // namespace

std::string htmlPageStart(const std::string& title) {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>\n<title>" +
         escapeHtml(title) + "</title>\n<style>" + kCss + "</style>\n</head>\n<body>\n<main>\n";
}

}  // namespace virtcom::report
