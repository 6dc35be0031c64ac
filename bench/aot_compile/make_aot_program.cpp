// make_aot_program SHAPE LINES: writes a large generated ST program to stdout, for measuring
// what `--backend aot` costs to compile as programs grow (bench/aot_compile/compile_cost.sh).
//   pou: one PROGRAM MAIN whose body has LINES statements (the worst case for one C function)
//   fbs: FUNCTION_BLOCKs of kFbLines statements each, chained by MAIN, LINES statements in all
// The statements mix what PLC code does (integer arithmetic, comparisons, IF, array accesses
// with constant and computed indexes, REAL arithmetic); values stay bounded by MOD, so a run
// never overflows or faults, and the same LINES always gives the same program.
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

constexpr int kInts = 16, kReals = 8, kArray = 64, kFbLines = 40;

std::string a(int i) { return "a" + std::to_string(((i % kInts) + kInts) % kInts); }
std::string x(int i) { return "x" + std::to_string(((i % kReals) + kReals) % kReals); }

// Statement number `i` of a body; `seed` varies the FBs so that no two are identical.
std::string statement(int i, int seed) {
  const int k = (i * 31 + seed * 17) % 97 + 1;
  switch ((i + seed) % 6) {
    case 0: return a(i) + " := (" + a(i + 3) + " + " + std::to_string(k) + " * " + a(i + 7) + ") MOD 100000;";
    case 1: return "IF " + a(i + 1) + " > " + std::to_string(k * 50) + " THEN " + a(i) + " := " + a(i) + " - " +
                   std::to_string(k) + "; ELSE " + a(i + 2) + " := " + a(i + 2) + " + 1; END_IF;";
    case 2: return "arr[" + std::to_string(i % kArray) + "] := (arr[" + std::to_string((i * 7) % kArray) + "] + " + a(i + 5) +
                   ") MOD 65536;";
    case 3: return x(i) + " := " + x(i + 1) + " * 0.5 + DINT_TO_REAL(" + a(i + 4) + " MOD 1000) * 0.25;";
    case 4: return "arr[(" + a(i + 6) + " MOD " + std::to_string(kArray) + " + " + std::to_string(kArray) + ") MOD " +
                   std::to_string(kArray) + "] := " + a(i) + " MOD 4096;";
    default: return "flag := flag XOR (" + a(i + 2) + " < " + a(i + 9) + ");";
  }
}

std::string declarations() {
  std::string s = "VAR\n  flag : BOOL;\n  arr : ARRAY[0.." + std::to_string(kArray - 1) + "] OF DINT;\n";
  for (int i = 0; i < kInts; ++i) s += "  " + a(i) + " : DINT := " + std::to_string(i * 13 + 1) + ";\n";
  for (int i = 0; i < kReals; ++i) s += "  " + x(i) + " : REAL := " + std::to_string(i) + ".5;\n";
  return s + "END_VAR\n";
}

void onePou(int lines) {
  std::string out = "PROGRAM MAIN\n" + declarations();
  for (int i = 0; i < lines; ++i) out += statement(i, 0) + "\n";
  std::fputs((out + "END_PROGRAM\n").c_str(), stdout);
}

void manyFbs(int lines) {
  const int fbs = lines / kFbLines > 0 ? lines / kFbLines : 1;
  for (int f = 0; f < fbs; ++f) {
    std::string out = "FUNCTION_BLOCK FB_" + std::to_string(f) + "\nVAR_INPUT in : DINT; END_VAR\nVAR_OUTPUT out : DINT; END_VAR\n" +
                      declarations() + a(0) + " := (" + a(0) + " + in) MOD 100000;\n";
    for (int i = 1; i + 1 < kFbLines; ++i) out += statement(i, f) + "\n";
    out += "out := " + a(f) + ";\nEND_FUNCTION_BLOCK\n";
    std::fputs(out.c_str(), stdout);
  }
  std::string main = "PROGRAM MAIN\nVAR\n";
  for (int f = 0; f < fbs; ++f) main += "  f" + std::to_string(f) + " : FB_" + std::to_string(f) + ";\n";
  main += "END_VAR\nf0(in := f" + std::to_string(fbs - 1) + ".out);\n";
  for (int f = 1; f < fbs; ++f) main += "f" + std::to_string(f) + "(in := f" + std::to_string(f - 1) + ".out);\n";
  std::fputs((main + "END_PROGRAM\n").c_str(), stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string shape = argc == 3 ? argv[1] : "";
  const int lines = argc == 3 ? std::atoi(argv[2]) : 0;
  if ((shape != "pou" && shape != "fbs") || lines < 1) {
    std::fprintf(stderr, "usage: make_aot_program pou|fbs LINES > program.st\n"
                         "  pou: one PROGRAM of LINES statements; fbs: FUNCTION_BLOCKs of %d statements, LINES in all\n",
                 kFbLines);
    return argc == 2 && std::string(argv[1]) == "--help" ? 0 : 64;
  }
  if (shape == "pou") onePou(lines);
  else manyFbs(lines);
  return 0;
}
