// Code generation: coverage probes (docs/coverage.md). A probe is one COVER instruction whose
// counter the driver places after code generation (compiler.cpp: placeCoverageCounters); until
// then its Bx is the probe's index in module.coverage.probes. Nothing here runs unless the
// program is compiled with CompileOptions::coverage, so code compiled without it is unchanged.
#include "lang/st/codegen/codegen.hpp"

namespace virtcom::st {

// The user's POUs: not the standard library, not the init program (FB_init calls).
bool PouCompiler::coversPou() const {
  return ctx_.coverage && !pou_.isLibrary && ctx_.module.pous[pou_.bcIndex].kind != bc::PouKind::Init;
}

void PouCompiler::probe(CoverageKind kind, SourceLocation loc, uint16_t arm, uint16_t arms, std::string name) {
  bc::CoverageTable& table = ctx_.module.coverage;
  emitBx(bc::Op::COVER, 0, static_cast<uint32_t>(table.probes.size()));
  table.probes.push_back({pou_.bcIndex, loc, kind, arm, arms, std::move(name)});
}

void PouCompiler::coverStatement(const Stmt& s) {
  switch (s.cover) {
    case CoverRole::Source:
      if (s.kind != StmtKind::Empty && s.kind != StmtKind::Label) probe(CoverageKind::Statement, s.loc);
      break;
    case CoverRole::StepActivated: probe(CoverageKind::Step, s.coverLoc, 0, 0, s.coverName); break;
    case CoverRole::TransitionFired: probe(CoverageKind::Transition, s.coverLoc, 0, 0, s.coverName); break;
    case CoverRole::Generated:
    case CoverRole::RuleFired: break;  // its probe is its THEN's (ifStatement)
  }
}

uint16_t PouCompiler::probedArms(const Stmt& s, size_t explicitArms) const {
  if (!covering_ || s.cover != CoverRole::Source) return 0;
  return static_cast<uint16_t>(explicitArms + 1);  // the ELSE, written or implicit
}

}  // namespace virtcom::st
