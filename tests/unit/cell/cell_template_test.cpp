// cell::CellTemplate and instantiateCell (the optimiser's reset, docs/optimise.md "Evaluation"):
// a cell built from the template is the cell loadCell gives, with its program copied, not
// compiled, and every instance is fresh; an edited value is checked at its own location.
#include <gtest/gtest.h>

#include "cell/cell.hpp"

namespace virtcom::cell {
namespace {

const std::string kGearbox = VIRTCOM_SOURCE_DIR "/examples/gearbox-cell/cell.yaml";

TEST(CellTemplate, InstancesAreLikeALoadedCellWithTheProgramCopied) {
  SourceManager sources;
  Diagnostics diags;
  auto tmpl = loadCellTemplate(kGearbox, sources, diags);
  ASSERT_TRUE(tmpl) << diags.render(sources);
  ASSERT_TRUE(tmpl->module);
  const size_t files = sources.fileCount();
  auto loaded = loadCell(kGearbox, sources, diags);
  ASSERT_TRUE(loaded);
  const size_t afterLoad = sources.fileCount();
  EXPECT_GT(afterLoad, files) << "loadCell reads the cell file and compiles its sources";
  auto a = instantiateCell(*tmpl, tmpl->root, sources, diags);
  auto b = instantiateCell(*tmpl, tmpl->root, sources, diags);
  ASSERT_TRUE(a && b) << diags.render(sources);
  EXPECT_EQ(a->devices.size(), loaded->devices.size());
  EXPECT_EQ(a->wires.size(), loaded->wires.size());
  EXPECT_EQ(a->bus.size(), loaded->bus.size());
  EXPECT_EQ(a->run.cycleDoneVar, "MAIN.cycleDone");
  EXPECT_EQ(a->module->code.size(), tmpl->module->code.size());
  EXPECT_NE(a->module.get(), tmpl->module.get()) << "each instance owns its copy of the image";
  EXPECT_NE(a->devices[0].get(), b->devices[0].get());
  EXPECT_EQ(sources.fileCount(), afterLoad) << "the instances read no file and compile nothing";
}

TEST(CellTemplate, EditedValueIsCheckedAtItsLocation) {
  SourceManager sources;
  Diagnostics diags;
  auto tmpl = loadCellTemplate(kGearbox, sources, diags);
  ASSERT_TRUE(tmpl);
  ConfigNode root = tmpl->root;
  // devices[0] is Robot1: its max_speed without a unit
  ConfigNode devices = ConfigNode::makeList(root.find("devices")->loc());
  for (const ConfigNode& d : root.find("devices")->items()) {
    if (devices.items().empty()) {
      ConfigNode robot = ConfigNode::makeMap(d.loc());
      for (const auto& [key, value] : d.entries())
        robot.add(key, d.keyLoc(key), key == "max_speed" ? ConfigNode::makeScalar("fast", value.loc()) : value);
      devices.push(robot);
    } else {
      devices.push(d);
    }
  }
  ConfigNode edited = ConfigNode::makeMap(root.loc());
  for (const auto& [key, value] : root.entries()) edited.add(key, root.keyLoc(key), key == "devices" ? devices : value);
  EXPECT_FALSE(instantiateCell(*tmpl, edited, sources, diags));
  EXPECT_NE(diags.render(sources).find("cell.yaml:40:16: error[C010]"), std::string::npos) << diags.render(sources);
}

}  // namespace
}  // namespace virtcom::cell
