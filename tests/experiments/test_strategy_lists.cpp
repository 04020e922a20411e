// Strategy lists read from the registries: a suite's {"every": FAMILY} items, advise's search
// space and the catalog `deepvox list --json` prints (strategies/shadow/strategy_catalog.h). A
// dummy storage registered in a child process reaches the built-in suites and advise with no
// other edit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "core/error.h"
#include "experiments/advise/advise_search.h"
#include "experiments/harness/suite_file.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/shadow/strategy_catalog.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {
namespace {

std::vector<RunItem> items_of(const std::string& strategies) {
  return expand_suite(parse_suite(R"({"suite": "x", "experiments": [{"name": "e", "kind": "shadow",
      "scene": "s.json", "params": {"res": 64}, "strategy": )" +
                                      strategies + "}]}",
                                  "every.json"));
}

std::vector<std::string> storages_of(const std::vector<RunItem>& items) {
  std::vector<std::string> out;
  for (const RunItem& item : items) out.push_back(item.params.at("storage"));
  return out;
}

TEST(EveryStrategy, ShadowMethodsTakeTheParametersTheyDeclare) {
  const std::vector<RunItem> items =
      items_of(R"([{"every": "shadow method", "params": {"slices": 64, "eps": 0.05}}])");
  std::vector<std::string> names;
  for (const RunItem& item : items) names.push_back(item.strategy);
  EXPECT_EQ(names, shadow_registry().names());
  for (const RunItem& item : items) {
    EXPECT_EQ(item.params.at("res"), "64");  // the experiment's own parameters stay
    EXPECT_EQ(item.params.count("slices"), item.strategy == "transmittance-slicemap" ? 1u : 0u);
    EXPECT_EQ(item.params.count("eps"), item.strategy == "dsm" || item.strategy == "auto");
  }
  // A method named before the item keeps its own parameters and runs once.
  const std::vector<RunItem> named =
      items_of(R"([{"name": "shadowmap", "params": {"pcf": 3}}, {"every": "shadow method"}])");
  EXPECT_EQ(named.size(), shadow_registry().names().size());
  EXPECT_EQ(named.front().params.at("pcf"), "3");
  EXPECT_EQ(std::count_if(named.begin(), named.end(),
                          [](const RunItem& item) { return item.strategy == "shadowmap"; }),
            1);
}

TEST(EveryStrategy, StoragesGoToTheNamedMethodWithTheirSizes) {
  EXPECT_EQ(storages_of(items_of(R"([{"every": "storage", "name": "dsm"}])")),
            storage_registry().names());
  // With sizes: a storage with a size knob once per value, but one that an earlier item runs
  // (avsm, with 2 nodes) is left to that item.
  const std::vector<RunItem> items = items_of(
      R"([{"name": "dsm", "params": {"storage": "avsm", "storage.nodes": 2}},
          {"every": "storage", "name": "dsm", "sizes": true}])");
  std::multiset<std::string> storages;
  std::set<std::string> sizes;
  for (const RunItem& item : items) {
    storages.insert(item.params.at("storage"));
    if (item.params.count("storage.frequencies"))
      sizes.insert(item.params.at("storage.frequencies"));
  }
  for (const CatalogEntry& e : catalog_of("storage"))
    EXPECT_EQ(storages.count(e.name),
              e.name == "avsm" ? 1 : std::max<size_t>(1, e.traits.sizes.size()))
        << e.name;
  EXPECT_EQ(sizes, (std::set<std::string>{"4", "8", "16", "32"}));
  EXPECT_EQ(items.front().params.at("storage.nodes"), "2");
}

TEST(EveryStrategy, BadItemsNameTheFileAndTheProblem) {
  for (const auto& [strategies, fragment] : std::vector<std::pair<std::string, std::string>>{
           {R"([{"every": "storages"}])", "unknown strategy family 'storages'"},
           {R"([{"every": "storage", "name": "reference"}])", "no parameter 'storage'"},
           {R"([{"every": "shadow method", "params": {"no_such_key": 1}}])",
            "no shadow method declares 'no_such_key'"},
           {R"([{"every": "voxelizer", "sizez": true}])", "sizez"}}) {
    try {
      items_of(strategies);
      ADD_FAILURE() << strategies << " loaded";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("every.json"), std::string::npos) << message;
      EXPECT_NE(message.find(fragment), std::string::npos) << fragment << " not in: " << message;
    }
  }
}

// Every shipped strategy declares its traits; a size knob is a parameter of its table whose
// every value builds the strategy, starting from its default; advise searches every storage
// that its traits do not leave out.
TEST(StrategyCatalog, TraitsAreDeclaredAndSizesBuild) {
  for (const CatalogEntry& e : strategy_catalog()) {
    EXPECT_TRUE(e.traits_declared) << e.registry << " " << e.name;
    EXPECT_FALSE(e.traits.family.empty() || e.traits.colour.empty()) << e.name;
    if (e.traits.size_key.empty()) continue;
    ASSERT_EQ(e.registry, "storage") << e.name;
    for (const std::string& size : e.traits.sizes)
      EXPECT_NO_THROW(storage_registry().create(
          e.name, StrategyParams(std::map<std::string, std::string>{{e.traits.size_key, size}})))
          << e.name << " " << size;
  }
  std::set<std::string> searched;
  for (const AdviseFamily& f : advise_space({true, true}))
    if (f.method == "dsm") searched.insert(f.fixed.at("storage"));
  for (const CatalogEntry& e : catalog_of("storage"))
    EXPECT_EQ(searched.count(e.name), e.traits.not_advised.empty() ? 1u : 0u) << e.name;
  const nlohmann::json json = strategy_catalog_json();
  EXPECT_EQ(json.at("strategies").size(), strategy_catalog().size());
}

class DummyStorage final : public DsmStorage {
 public:
  std::string name() const override { return "dummy"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }
  void generate(const DsmGenerationContext&) override { throw Error("the dummy stores nothing"); }
  DsmReader reader() const override { throw Error("the dummy stores nothing"); }
  int64_t bytes_allocated() const override { return 0; }
  bool keeps_error_bound() const override { return false; }
  int64_t bytes_per_node() const override { return 0; }
};

// Registered in a child process (death-test fork), so the other tests keep the shipped registry.
int dummy_storage_failures() {
  storage_registry().add("dummy", "a storage that stores nothing", {},
                         [](const StrategyParams&) { return std::make_unique<DummyStorage>(); });
  int failures = 0;
  const auto expect = [&](bool ok, const char* what) {
    if (!ok) std::fprintf(stderr, "missing: %s\n", what), ++failures;
  };
  const auto runs_dummy = [](const std::string& suite, const std::string& experiment) {
    const std::vector<RunItem> items = expand_suite(load_suite(resolve_suite_path(suite)));
    return std::any_of(items.begin(), items.end(), [&](const RunItem& item) {
      return item.experiment_name == experiment && item.strategy == "dsm" &&
             item.params.count("storage") && item.params.at("storage") == "dummy";
    });
  };
  expect(runs_dummy("quick", "dsm-storage"), "quick's dsm-storage runs the dummy");
  expect(runs_dummy("accuracy", "methods"), "accuracy's methods run the dummy");
  const std::vector<AdviseFamily> space = advise_space({true, true});
  expect(std::any_of(space.begin(), space.end(),
                     [](const AdviseFamily& f) {
                       return f.method == "dsm" && f.fixed.at("storage") == "dummy" &&
                              f.axes.size() == 1 && f.axes[0].key == "res";
                     }),
         "advise searches the dummy over res");
  bool listed = false;
  const nlohmann::json catalog = strategy_catalog_json();
  for (const nlohmann::json& e : catalog.at("strategies"))
    listed |= e.at("name").get<std::string>() == "dummy" &&
              e.at("registry").get<std::string>() == "storage" &&
              !e.at("family").get<std::string>().empty() &&
              !e.at("colour").get<std::string>().empty();
  expect(listed, "deepvox list --json lists the dummy with a family and a colour");
  return failures;
}

TEST(StrategyCatalogDeathTest, ARegisteredStorageReachesSuitesAdviseAndTheList) {
  EXPECT_EXIT(std::exit(dummy_storage_failures()), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace dv
