// rostest: every topic and service the running node offers or takes, and every parameter it
// reads, is named in docs/interface.md, so that the document cannot fall behind the node.
// Topics and services come from the master (the node's code may be arranged in any way);
// parameters from the literal names passed to the parameter-reading calls in src/node and the
// names of cfg/Physics.cfg.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <ros/master.h>
#include <ros/ros.h>
#include <ros/service.h>

namespace {

const std::string kNode = "/ragdoll_sim";
const std::string kDoc = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/docs/interface.md";

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A name counts as documented when it appears in backticks, bare or with a leading ~ or /.
bool documented(const std::string& doc, const std::string& name) {
  for (const std::string& form : {name, "~" + name, "/" + name})
    if (doc.find("`" + form + "`") != std::string::npos) return true;
  return false;
}

// Every name the master lists for our node: "topic out|in|service" -> names.
std::map<std::string, std::set<std::string>> nodeInterface() {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  std::map<std::string, std::set<std::string>> out;
  if (!ros::master::execute("getSystemState", args, result, payload, true)) return out;
  const char* kinds[3] = {"published topic", "subscribed topic", "service"};
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < payload[k].size(); ++i)
      for (int j = 0; j < payload[k][i][1].size(); ++j)
        if (std::string(payload[k][i][1][j]) == kNode) out[kinds[k]].insert(payload[k][i][0]);
  return out;
}

// roscpp gives every node these; they are not ours to document.
bool standard(const std::string& name) {
  return name == "/rosout" || name == kNode + "/get_loggers" || name == kNode + "/set_logger_level";
}

}  // namespace

TEST(InterfaceDoc, EveryTopicAndServiceOfTheNodeIsDocumented) {
  const std::string doc = readFile(kDoc);
  ASSERT_FALSE(doc.empty()) << kDoc << " missing";
  ASSERT_TRUE(ros::service::waitForService(kNode + "/step", ros::Duration(60)))
      << "the node did not come up";
  ros::WallDuration(2.0).sleep();  // the interactive marker server and publishers come last
  const auto found = nodeInterface();
  ASSERT_TRUE(found.count("published topic") && found.count("service"))
      << "the master listed nothing for " << kNode;
  size_t checked = 0;
  for (const auto& [kind, names] : found)
    for (const std::string& name : names) {
      if (standard(name)) continue;
      ++checked;
      std::printf("interface_doc: %s %s\n", kind.c_str(), name.c_str());
      EXPECT_TRUE(documented(doc, name))
          << "docs/interface.md lacks the " << kind << " `" << name << "`";
    }
  EXPECT_GT(checked, 20u);
}

TEST(InterfaceDoc, EveryParameterTheNodeReadsIsDocumented) {
  const std::string doc = readFile(kDoc);
  ASSERT_FALSE(doc.empty()) << kDoc << " missing";
  // read(pnh, "name", ...), getParam("name"), hasParam("name"), ros::param::param("name"), ...
  const std::regex call(R"re(\b(?:read|\w*[pP]aram\w*)\s*\(\s*(?:[\w.:>-]+\s*,\s*)?"([^"]+)")re");
  const std::regex cfg(R"re(\bgen\.add\(\s*"([^"]+)")re");
  std::map<std::string, std::string> names;  // name -> file it is read in
  const std::filesystem::path root(RAGDOLL_SIM_SOURCE_DIR);
  for (const auto& e : std::filesystem::recursive_directory_iterator(root / "src/node")) {
    const std::string ext = e.path().extension();
    if (ext != ".cpp" && ext != ".hpp") continue;
    const std::string text = readFile(e.path());
    for (std::sregex_iterator m(text.begin(), text.end(), call), end; m != end; ++m)
      names.emplace((*m)[1], std::filesystem::relative(e.path(), root));
  }
  const std::string physics = readFile(root / "cfg/Physics.cfg");
  for (std::sregex_iterator m(physics.begin(), physics.end(), cfg), end; m != end; ++m)
    names.emplace((*m)[1], "cfg/Physics.cfg");
  EXPECT_GT(names.size(), 60u) << "the scan found too few parameters; did the reading calls change?";
  for (const auto& [name, file] : names)
    EXPECT_TRUE(documented(doc, name.front() == '~' ? name.substr(1) : name))
        << "docs/interface.md lacks the parameter `" << name << "` (read in " << file << ")";
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "interface_doc");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
