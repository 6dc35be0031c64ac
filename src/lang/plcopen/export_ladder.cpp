// A POU's ladder rungs (st::Pou::ladder) as a TC6 <LD> body (export_internal.hpp).
#include <pugixml.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "lang/plcopen/export_internal.hpp"

namespace virtcom::plcopen::detail {

namespace {

// Grid of the drawing: contacts left to right in series, parallel branches and the outputs one
// below the other. The importer (and vendor tools) run a rung's outputs top to bottom, so the
// outputs are stacked in the order the rung lists them.
constexpr int kColumn = 60, kRow = 40, kRungGap = 20, kLeft = 20;
constexpr int kContactWidth = 21, kContactHeight = 20;

class LadderWriter {
 public:
  explicit LadderWriter(pugi::xml_node ld) : ld_(ld) {}

  void rung(const st::LadderRung& r) {
    if (!r.comment.empty()) comment(r.comment);
    Placed rail = element("leftPowerRail", kLeft, top_, 3, kRow);
    rail.node.append_child("connectionPointOut").append_attribute("formalParameter") = "";
    Extent extent{1, 1};
    std::vector<Source> power = condition(r.condition, {{rail.localId, ""}}, 1, top_, extent);
    int outputX = kLeft + (extent.columns + 1) * kColumn;
    std::vector<Source> drawn;
    int y = top_;
    for (const st::LadderOutput& out : r.outputs) {
      drawn.push_back(output(out, power, outputX, y));
      y += out.kind == st::LadderOutput::Kind::Block ? 2 * kRow : kRow;
    }
    int bottom = std::max(y, top_ + extent.rows * kRow);
    Placed right = element("rightPowerRail", outputX + 3 * kColumn, top_, 3, bottom - top_);
    connect(right.node.append_child("connectionPointIn"), drawn);
    top_ = bottom + kRungGap;
  }

 private:
  struct Placed {
    pugi::xml_node node;
    uint32_t localId;
  };
  // An output a connection reads: the element and, for a block, which of its outputs.
  struct Source {
    uint32_t localId;
    const char* formal;
  };
  struct Extent {
    int columns, rows;  // grid cells the condition takes, from its top-left corner
  };

  Placed element(const char* name, int x, int y, int width, int height) {
    pugi::xml_node node = ld_.append_child(name);
    uint32_t id = ++lastId_;
    node.append_attribute("localId") = id;
    node.append_attribute("height") = height;
    node.append_attribute("width") = width;
    pugi::xml_node position = node.append_child("position");
    position.append_attribute("x") = x;
    position.append_attribute("y") = y;
    return {node, id};
  }

  // Several connections into one point are the wired OR of parallel branches.
  static void connect(pugi::xml_node pointIn, const std::vector<Source>& sources) {
    for (const Source& s : sources) {
      pugi::xml_node c = pointIn.append_child("connection");
      c.append_attribute("refLocalId") = s.localId;
      if (s.formal[0]) c.append_attribute("formalParameter") = s.formal;
    }
  }

  void comment(const std::string& text) {
    Placed c = element("comment", kLeft, top_, 300, kContactHeight);
    c.node.append_child("content").append_child("xhtml:p").append_child(pugi::node_cdata).set_value(text.c_str());
    top_ += kRow;
  }

  // Draws the condition fed by `power` with its top-left contact at grid cell (column, y);
  // returns the points whose OR is the power after it. `extent` gets the last column and the
  // lowest row (counted from the rung's top, 1-based) it takes.
  std::vector<Source> condition(const st::LadderCondition& c, std::vector<Source> power, int column, int y, Extent& extent) {
    using Kind = st::LadderCondition::Kind;
    Extent own{column, (y - top_) / kRow + 1};
    std::vector<Source> out;
    switch (c.kind) {
      case Kind::Contact: {
        Placed contact = element("contact", kLeft + column * kColumn, y, kContactWidth, kContactHeight);
        contact.node.append_attribute("negated") = c.negated ? "true" : "false";
        connect(contact.node.append_child("connectionPointIn"), power);
        contact.node.append_child("connectionPointOut");
        contact.node.append_child("variable").text().set(c.variable.c_str());
        out = {{contact.localId, ""}};
        break;
      }
      case Kind::Series:  // each operand after the one before, on the same row
        out = std::move(power);
        for (const st::LadderCondition& operand : c.operands) {
          Extent part = own;
          out = condition(operand, std::move(out), column, y, part);
          column = part.columns + 1;
          own = {std::max(own.columns, part.columns), std::max(own.rows, part.rows)};
        }
        break;
      case Kind::Parallel:  // each branch below everything drawn before, all fed by `power`
        for (const st::LadderCondition& operand : c.operands) {
          Extent part = own;
          int row = out.empty() ? y : top_ + own.rows * kRow;
          std::vector<Source> branch = condition(operand, power, column, row, part);
          out.insert(out.end(), branch.begin(), branch.end());
          own = {std::max(own.columns, part.columns), std::max(own.rows, part.rows)};
        }
        break;
    }
    extent = own;
    return out;
  }

  Source output(const st::LadderOutput& out, const std::vector<Source>& power, int x, int y) {
    using Kind = st::LadderOutput::Kind;
    if (out.kind == Kind::Block) return block(out, power, x, y);
    Placed coil = element("coil", x, y, kContactWidth, kContactHeight);
    coil.node.append_attribute("negated") = out.kind == Kind::NegatedCoil ? "true" : "false";
    if (out.kind == Kind::SetCoil) coil.node.append_attribute("storage") = "set";
    if (out.kind == Kind::ResetCoil) coil.node.append_attribute("storage") = "reset";
    connect(coil.node.append_child("connectionPointIn"), power);
    coil.node.append_child("connectionPointOut");
    coil.node.append_child("variable").text().set(out.variable.c_str());
    return {coil.localId, ""};
  }

  // The block with the rung's power on one input and a constant (an inVariable to its left) on
  // another, if it has one; its state output goes on to the right rail, as a timer sits in a rung.
  Source block(const st::LadderOutput& out, const std::vector<Source>& power, int x, int y) {
    Placed b = element("block", x, y, 60, 2 * kRow);
    b.node.append_attribute("typeName") = out.blockType.c_str();
    b.node.append_attribute("instanceName") = out.variable.c_str();
    pugi::xml_node inputs = b.node.append_child("inputVariables");
    auto input = [&](const std::string& formal, const std::vector<Source>& sources) {
      pugi::xml_node v = inputs.append_child("variable");
      v.append_attribute("formalParameter") = formal.c_str();
      connect(v.append_child("connectionPointIn"), sources);
    };
    input(out.powerInput, power);
    if (!out.constantInput.empty()) {
      Placed constant = element("inVariable", x - kColumn, y + kRow, 40, kContactHeight);
      constant.node.append_child("connectionPointOut");
      constant.node.append_child("expression").text().set(out.constantValue.c_str());
      input(out.constantInput, {{constant.localId, ""}});
    }
    b.node.append_child("inOutVariables");
    pugi::xml_node q = b.node.append_child("outputVariables").append_child("variable");
    q.append_attribute("formalParameter") = out.stateOutput.c_str();
    q.append_child("connectionPointOut");
    return {b.localId, out.stateOutput.c_str()};
  }

  pugi::xml_node ld_;
  uint32_t lastId_ = 0;
  int top_ = 10;
};

}  // namespace

void writeLadderBody(pugi::xml_node parent, const st::Ladder& ladder) {
  LadderWriter writer(parent.append_child("body").append_child("LD"));
  for (const st::LadderRung& rung : ladder.rungs) writer.rung(rung);
}

}  // namespace virtcom::plcopen::detail
