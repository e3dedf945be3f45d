// The resolved echo (Scene::resolved_json), made by the scene reader's reads
// (src/io/toml_reader.hpp): it fills in every default, and it is itself a
// scene that reads into the same world and echoes itself.
#include "gjkdem/io/scene.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include <filesystem>
#include <sstream>
#include <string>

namespace gjkdem::io {
namespace {

using Json = nlohmann::ordered_json;

// A JSON value as the TOML node it was read from.
void insert_toml(toml::table& into, const std::string& key, const Json& j);

toml::array toml_array(const Json& j) {
  toml::array a;
  for (const Json& e : j) {
    if (e.is_object()) {
      toml::table t;
      for (const auto& [k, v] : e.items()) insert_toml(t, k, v);
      a.push_back(std::move(t));
    } else if (e.is_array()) {
      a.push_back(toml_array(e));
    } else if (e.is_number_integer()) {
      a.push_back(e.get<std::int64_t>());
    } else if (e.is_number()) {
      a.push_back(e.get<double>());
    } else if (e.is_boolean()) {
      a.push_back(e.get<bool>());
    } else {
      a.push_back(e.get<std::string>());
    }
  }
  return a;
}

void insert_toml(toml::table& into, const std::string& key, const Json& j) {
  if (j.is_object()) {
    toml::table t;
    for (const auto& [k, v] : j.items()) insert_toml(t, k, v);
    into.insert(key, std::move(t));
  } else if (j.is_array()) {
    into.insert(key, toml_array(j));
  } else if (j.is_number_integer()) {
    into.insert(key, j.get<std::int64_t>());
  } else if (j.is_number()) {
    into.insert(key, j.get<double>());
  } else if (j.is_boolean()) {
    into.insert(key, j.get<bool>());
  } else {
    into.insert(key, j.get<std::string>());
  }
}

// The echo as a scene: dt_auto says how dt was found and is no key.
std::string echo_as_scene(Json echo) {
  echo["simulation"].erase("dt_auto");
  toml::table root;
  for (const auto& [k, v] : echo.items()) insert_toml(root, k, v);
  std::ostringstream text;
  text << root;
  return text.str();
}

// Compared as unordered objects: the TOML written sorts the keys.
nlohmann::json echo_of(const Scene& s) {
  nlohmann::json j = nlohmann::json::parse(s.resolved_json);
  j["simulation"].erase("dt_auto");
  return j;
}

TEST(SceneEcho, FillsInEveryDefault) {
  const Scene s = load_scene(R"(
[simulation]
duration = 0.2
[[material]]
name = "rock"
density = 2000.0
youngs_modulus = 1.0e7
[[wall]]
type = "box"
min = [-0.1, -0.1, -0.1]
max = [0.1, 0.1, 0.1]
material = "rock"
[[body]]
shape = { type = "sphere", radius = 0.01 }
material = "rock"
velocity = [0.0, 0.0, -1.0]
)",
                             "defaults.toml", ".");
  const Json echo = Json::parse(s.resolved_json);
  EXPECT_EQ(echo["simulation"]["dt_auto"], true);
  EXPECT_EQ(echo["simulation"]["dt"], s.dt);
  EXPECT_EQ(echo["simulation"]["seed"], 1);
  EXPECT_EQ(echo["simulation"]["guards"], "stop");
  // Tables not written come with their defaults.
  EXPECT_EQ(echo["output"]["dir"], "out");
  EXPECT_EQ(echo["output"]["every"], 0.2 / 100);
  EXPECT_EQ(echo["output"]["checkpoint_every"], s.checkpoint_every);
  EXPECT_EQ(echo["contact"]["model"], "volume");
  EXPECT_EQ(echo["material"][0]["friction"], s.world.materials.at(0).friction);
  EXPECT_EQ(echo["wall"][0]["thickness"], 0.1) << "the box's default: half its least size";
  EXPECT_EQ(echo["wall"][0]["open_top"], false);
  const Json& body = echo["body"][0];
  EXPECT_EQ(body["shape"]["type"], "sphere") << "a shape as written";
  EXPECT_EQ(body["position"], Json::parse("[0.0, 0.0, 0.0]"));
  EXPECT_EQ(body["velocity"], Json::parse("[0.0, 0.0, -1.0]"));
  EXPECT_EQ(body["rotation"], Json::parse("[1.0, 0.0, 0.0, 0.0]"));
  EXPECT_EQ(body["fixed"], false);
  EXPECT_FALSE(body.contains("motion")) << "an optional table not given is not made up";
}

// Reads `first`'s echo as a scene: it must echo itself and give the same world.
void expect_echo_reads_back(const Scene& first, const std::filesystem::path& base) {
  const std::string again_text = echo_as_scene(Json::parse(first.resolved_json));
  const Scene again = load_scene(again_text, "the echo", base);
  EXPECT_EQ(echo_of(again), echo_of(first)) << again_text;
  EXPECT_EQ(again.dt, first.dt);
  EXPECT_EQ(again.duration, first.duration);
  EXPECT_EQ(again.output_every, first.output_every);
  const dem::World &a = first.world, &b = again.world;
  ASSERT_EQ(b.bodies.size(), a.bodies.size());
  EXPECT_EQ(b.templates.size(), a.templates.size());
  EXPECT_EQ(b.materials.size(), a.materials.size());
  EXPECT_EQ(b.planes.size(), a.planes.size());
  EXPECT_EQ(b.inflows.size(), a.inflows.size());
  EXPECT_EQ(b.bonds.size(), a.bonds.size());
  EXPECT_EQ(b.settings.gravity, a.settings.gravity);
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQ(b.bodies[i].position, a.bodies[i].position) << "body " << i;
    const Quat &qa = a.bodies[i].orientation, &qb = b.bodies[i].orientation;
    EXPECT_TRUE(qa.w == qb.w && qa.x == qb.x && qa.y == qb.y && qa.z == qb.z) << "body " << i;
    EXPECT_EQ(b.bodies[i].velocity, a.bodies[i].velocity) << "body " << i;
    EXPECT_EQ(b.bodies[i].fixed, a.bodies[i].fixed) << "body " << i;
  }
}

TEST(SceneEcho, IsASceneThatReadsIntoTheSameWorld) {
  namespace fs = std::filesystem;
  {
    SCOPED_TRACE("the default scene");
    expect_echo_reads_back(load_scene(default_scene_toml(), "default", "."), ".");
  }
  int scenes = 0;
  for (const char* folder : {"/examples/scenes", "/tests/data/scenes"}) {
    for (const fs::directory_entry& e : fs::directory_iterator(std::string(GJKDEM_SOURCE_DIR) + folder)) {
      if (e.path().extension() != ".toml") continue;
      SCOPED_TRACE(e.path().string());
      expect_echo_reads_back(load_scene_file(e.path()), e.path().parent_path());
      ++scenes;
    }
  }
  EXPECT_GE(scenes, 19);  // the example and test scenes, all found
}

}  // namespace
}  // namespace gjkdem::io
