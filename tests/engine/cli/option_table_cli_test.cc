// Every command's flags against the option table (engine/pipeline/option_table.h): a flag named
// as an option has the option's type and default, whether the command declares it from the table
// (AddTableFlags) or on its own; `mine` takes every option; and every option of `mine` refuses a
// value outside its range or of another kind with a usage error naming the flag, before any work.
// The commands describe their flags with the hidden `--options-json`.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "engine/pipeline/option_table.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::RunResult;
using testing::RunTool;

const char* const kCommands[] = {
    "mine",    "reindex",         "import",   "info",    "verify", "export", "synth",
    "trellis", "inspect-trellis", "grow",     "cluster", "report", "score",  "export-motif",
    "words",   "search",          "classify", "segment", "graph"};

nlohmann::json CommandOptions(const std::string& command) {
  const RunResult run = RunTool(command + " --options-json");
  EXPECT_EQ(run.exit_code, 0) << command << "\n" << run.output;
  return nlohmann::json::parse(run.output, nullptr, /*allow_exceptions=*/false);
}

// The value types a flag of each table type may be declared with.
bool TypeFits(OptionType type, const std::string& declared) {
  if (declared == "string") return type != OptionType::kSwitch;
  if (declared == "switch") return type == OptionType::kSwitch;
  if (declared == "uint32" || declared == "uint64" || declared == "int") {
    return type == OptionType::kCount || type == OptionType::kInteger;
  }
  if (declared == "double" || declared == "float") return type == OptionType::kNumber;
  return false;
}

TEST(OptionTableCli, EveryCommandsFlagsAreTheTablesInNameTypeAndDefault) {
  size_t table_flags = 0;
  for (const char* command : kCommands) {
    const nlohmann::json options = CommandOptions(command);
    ASSERT_TRUE(options.is_array()) << command;
    for (const nlohmann::json& option : options) {
      const std::string name = option["name"];
      const OptionSpec* spec = FindMineOption(name);
      if (spec == nullptr || spec->info.name != name) continue;  // the command's own flag
      const std::string where = std::string(command) + " --" + name;
      EXPECT_TRUE(TypeFits(spec->type, option["type"])) << where << ": " << option.dump();
      const bool recorded = std::string(command) == "reindex" && option["default"].is_null();
      if (spec->type == OptionType::kSwitch || recorded) continue;
      // A text option's empty default may be shown or not.
      const std::string shown = option["default"].is_null() ? "" : option["default"];
      EXPECT_EQ(shown, spec->info.default_value) << where;
      table_flags += option["table"].get<bool>();
    }
  }
  EXPECT_GT(table_flags, 60u);
}

TEST(OptionTableCli, MineTakesEveryOptionFromTheTable) {
  const nlohmann::json options = CommandOptions("mine");
  std::set<std::string> flags;
  for (const nlohmann::json& option : options) {
    if (option["table"]) flags.insert(option["name"].get<std::string>());
  }
  for (const OptionSpec& spec : MineOptionSpecs()) EXPECT_TRUE(flags.count(spec.info.name));
}

// A value no option of its type accepts, for every non-text option of `mine`: exit 2, the flag
// named, nothing written.
TEST(OptionTableCli, EveryOptionRefusesAnImpossibleValueNamingItsFlag) {
  testing::TempDir dir;
  for (const OptionSpec& spec : MineOptionSpecs()) {
    std::string value;
    switch (spec.type) {
      case OptionType::kCount:
      case OptionType::kInteger:
        value = "-7";
        break;
      case OptionType::kNumber:
        value = "nan";
        break;
      case OptionType::kChoice:
      case OptionType::kGroups:
      case OptionType::kRadius:
      case OptionType::kLength:
        value = "nonsense";
        break;
      case OptionType::kText:
      case OptionType::kSwitch:
        continue;
    }
    const std::string flag = "--" + spec.info.name;
    const RunResult run =
        RunTool("mine --out " + dir.File("out") + " " + flag + " " + value + " --quiet");
    EXPECT_EQ(run.exit_code, 2) << flag << "\n" << run.output;
    EXPECT_NE(run.output.find(flag + " must be"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("'" + value + "'"), std::string::npos) << run.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.File("out")));
}

}  // namespace
}  // namespace motif
