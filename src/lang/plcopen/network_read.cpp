// Reads an <LD> or <FBD> body into a Network; see network.hpp.
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "lang/plcopen/diagnostic_codes.hpp"
#include "lang/plcopen/network_translate.hpp"

namespace virtcom::plcopen::detail {

namespace {

struct KindName {
  std::string_view element;
  ElementKind kind;
};

constexpr KindName kKinds[] = {
    {"leftPowerRail", ElementKind::LeftRail},   {"rightPowerRail", ElementKind::RightRail},
    {"contact", ElementKind::Contact},          {"coil", ElementKind::Coil},
    {"inVariable", ElementKind::InVariable},    {"outVariable", ElementKind::OutVariable},
    {"inOutVariable", ElementKind::InOutVariable}, {"block", ElementKind::Block},
    {"connector", ElementKind::Connector},      {"continuation", ElementKind::Continuation},
    {"jump", ElementKind::Jump},                {"label", ElementKind::Label},
    {"return", ElementKind::Return},            {"comment", ElementKind::Comment},
};

const KindName* kindOf(std::string_view element) {
  for (const auto& k : kKinds)
    if (k.element == element) return &k;
  return nullptr;
}

bool parseUint(std::string_view text, uint32_t& out) {
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size() && !text.empty();
}

bool isTrue(pugi::xml_attribute a) {
  std::string_view v = a.value();
  return v == "true" || v == "1";
}

Edge edgeOf(pugi::xml_node node) {
  std::string_view v = node.attribute("edge").value();
  if (v == "rising") return Edge::Rising;
  if (v == "falling") return Edge::Falling;
  return Edge::None;
}

class NetworkReader {
 public:
  NetworkReader(Importer& imp, Network& net) : imp_(imp), net_(net) {}

  void read(pugi::xml_node body) {
    for (pugi::xml_node node = body.first_child(); node; node = node.next_sibling()) {
      if (node.type() != pugi::node_element) continue;
      std::string_view name = localName(node);
      const KindName* kind = kindOf(name);
      if (net_.inChart) {
        readChartElement(node, kind);
        continue;
      }
      if (!kind) {
        if (name != "addData" && name != "documentation")
          imp_.unsupported(node, "<" + std::string(name) + "> in " + (net_.ladder ? "an LD" : "an FBD") + " body");
        continue;
      }
      readElement(node, kind->kind);
    }
    countConsumers();
  }

 private:
  // In an SFC body the chart reader reports the SFC elements; LD/FBD elements only compute the
  // values that transition conditions read, so elements that would run statements are refused.
  void readChartElement(pugi::xml_node node, const KindName* kind) {
    if (localName(node) == "transition") {
      pugi::xml_node wired = child(child(node, "condition"), "connectionPointIn");
      if (!wired) return;
      Element e;
      e.kind = ElementKind::Condition;
      e.node = node;
      if (!readLocalId(node, e.localId)) return;
      e.inputs.push_back(readPin(wired));
      add(std::move(e));
      return;
    }
    if (!kind) return;
    switch (kind->kind) {
      case ElementKind::Coil: case ElementKind::OutVariable: case ElementKind::InOutVariable:
      case ElementKind::RightRail: case ElementKind::Jump: case ElementKind::Label: case ElementKind::Return:
        imp_.unsupported(node, "<" + std::string(localName(node)) +
                                   "> in an SFC body (its LD/FBD elements may only compute transition conditions)");
        return;
      default: readElement(node, kind->kind);
    }
  }

  void readElement(pugi::xml_node node, ElementKind kind) {
    Element e;
    e.kind = kind;
    e.node = node;
    if (kind != ElementKind::Comment && !readLocalId(node, e.localId)) return;
    uint32_t order = 0;
    if (node.attribute("executionOrderId") && parseUint(node.attribute("executionOrderId").value(), order))
      e.executionOrder = order;
    if (pugi::xml_node pos = child(node, "position")) {
      e.positioned = true;
      e.x = std::strtod(pos.attribute("x").value(), nullptr);
      e.y = std::strtod(pos.attribute("y").value(), nullptr);
      if (!std::isfinite(e.x) || !std::isfinite(e.y)) e.x = e.y = 0;  // keeps the execution-order sort well defined
    }
    e.negated = isTrue(node.attribute(kind == ElementKind::InOutVariable ? "negatedIn" : "negated"));
    e.negatedOut = isTrue(node.attribute("negatedOut"));
    e.edge = edgeOf(node);
    std::string_view storage = node.attribute("storage").value();
    e.storage = storage == "set" ? Storage::Set : storage == "reset" ? Storage::Reset : Storage::None;
    if (kind == ElementKind::Block) {
      readBlock(node, e);
    } else {
      for (pugi::xml_node in : children(node, "connectionPointIn")) e.inputs.push_back(readPin(in));
      e.name = kind == ElementKind::Jump || kind == ElementKind::Label ? node.attribute("label").value()
                                                                      : node.attribute("name").value();
    }
    add(std::move(e));
  }

  void add(Element e) {
    if (net_.byLocalId.count(e.localId) && e.kind != ElementKind::Comment) {
      if (!net_.inChart)  // the chart reader checks the localIds of all the elements of an SFC body
        imp_.error(diag::X007, e.node, describe(e.node) + ": localId " + std::to_string(e.localId) +
                                           " is already used by another element of this body");
      return;
    }
    if (e.kind != ElementKind::Comment) net_.byLocalId[e.localId] = net_.elements.size();
    net_.elements.push_back(std::move(e));
  }

  bool readLocalId(pugi::xml_node node, uint32_t& id) {
    pugi::xml_attribute attr = node.attribute("localId");
    if (!attr) {
      imp_.error(diag::X003, node, "<" + std::string(localName(node)) + "> has no 'localId' attribute");
      return false;
    }
    if (!parseUint(attr.value(), id)) {
      imp_.error(diag::X005, node, std::string("localId '") + attr.value() + "' is not a whole number");
      return false;
    }
    return true;
  }

  Pin readPin(pugi::xml_node pointIn) {
    Pin pin;
    pin.node = pointIn;
    for (pugi::xml_node c : children(pointIn, "connection")) {
      Connection conn;
      conn.node = c;
      conn.formal = c.attribute("formalParameter").value();
      if (!parseUint(c.attribute("refLocalId").value(), conn.refLocalId)) {
        imp_.error(diag::X005, c, std::string("<connection> refLocalId '") + c.attribute("refLocalId").value() +
                                      "' is not a whole number");
        continue;
      }
      pin.sources.push_back(std::move(conn));
    }
    return pin;
  }

  void readBlock(pugi::xml_node node, Element& e) {
    e.name = node.attribute("typeName").value();
    e.instanceName = node.attribute("instanceName").value();
    if (e.name.empty()) imp_.error(diag::X003, node, describe(node) + " has no 'typeName' attribute");
    for (pugi::xml_node v : children(child(node, "inputVariables"), "variable")) {
      Pin pin = readPin(child(v, "connectionPointIn"));
      pin.node = v;
      pin.formal = v.attribute("formalParameter").value();
      pin.negated = isTrue(v.attribute("negated"));
      pin.edge = edgeOf(v);
      e.inputs.push_back(std::move(pin));
    }
    for (pugi::xml_node v : children(child(node, "inOutVariables"), "variable")) {
      Pin pin = readPin(child(v, "connectionPointIn"));
      pin.node = v;
      pin.formal = v.attribute("formalParameter").value();
      e.outputs.push_back({pin.formal, false, true});
      e.inputs.push_back(std::move(pin));
    }
    for (pugi::xml_node v : children(child(node, "outputVariables"), "variable"))
      e.outputs.push_back({v.attribute("formalParameter").value(), isTrue(v.attribute("negated")), false});
  }

  // Connections to a continuation read the connector of the same name: redirect them there, so
  // consumer counts (and later values) need not know about continuations.
  void countConsumers() {
    for (Element& e : net_.elements)
      for (Pin& pin : e.inputs)
        for (Connection& conn : pin.sources) {
          size_t target = net_.find(conn.refLocalId);
          if (target == kNoElement) continue;
          if (net_.elements[target].kind == ElementKind::Continuation) {
            size_t connector = connectorNamed(net_.elements[target].name);
            if (connector == kNoElement) continue;  // reported when translated
            conn.refLocalId = net_.elements[connector].localId;
            target = connector;
          }
          if (e.kind != ElementKind::RightRail) ++net_.elements[target].consumers;  // the rail reads nothing
        }
  }

  size_t connectorNamed(const std::string& name) const {
    for (size_t i = 0; i < net_.elements.size(); ++i)
      if (net_.elements[i].kind == ElementKind::Connector && net_.elements[i].name == name) return i;
    return kNoElement;
  }

  Importer& imp_;
  Network& net_;
};

}  // namespace

Network readNetwork(Importer& imp, pugi::xml_node body, bool ladder) {
  Network net;
  net.ladder = ladder;
  NetworkReader(imp, net).read(body);
  return net;
}

Network readChartNetwork(Importer& imp, pugi::xml_node sfc) {
  Network net;
  net.inChart = true;
  NetworkReader(imp, net).read(sfc);
  return net;
}

bool isNetworkElement(std::string_view element) { return kindOf(element) != nullptr; }

}  // namespace virtcom::plcopen::detail
