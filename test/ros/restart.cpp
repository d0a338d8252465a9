// rostest: start-up after a crash. The test runs the node binary as a child (as `rosrun`
// would), reconfigures it, spawns a ragdoll, kills it with SIGKILL and starts it again: the
// new node's log names the values it inherited from the parameter server, and the dead node's
// ragdoll parameters are deleted, not taken for a ragdoll of the new node. A clean shutdown
// (SIGINT) deletes the spawned ragdolls' parameters.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

#include <ragdoll_sim/SpawnRagdoll.h>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

const std::string kName = "restart_sim";
const std::string kNode = "/" + kName;
const std::string kUrdf = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/ragdoll.urdf";

// The node binary as a child, stdout and stderr to `log`; its pid.
pid_t startNode(const std::string& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    setenv("ROSCONSOLE_STDOUT_LINE_BUFFERED", "1", 1);
    const std::string name = "__name:=" + kName, urdf = "_urdf_file:=" + kUrdf;
    execl(RAGDOLL_SIM_NODE_BIN, RAGDOLL_SIM_NODE_BIN, name.c_str(), urdf.c_str(),
          "_paused:=true", static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

// Exit status of the child after `sig`, or -1.
int stopNode(pid_t pid, int sig) {
  kill(pid, sig);
  int status = 0;
  for (int i = 0; i < 300; ++i) {  // 30 s
    if (waitpid(pid, &status, WNOHANG) == pid)
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    usleep(100000);
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool spawn(const std::string& name, std::string* message) {
  ragdoll_sim::SpawnRagdoll s;
  s.request.name = name;
  s.request.urdf_file = kUrdf;
  s.request.pose.position.x = 3.0;
  s.request.pose.position.z = 2.0;
  const bool ok = ros::service::call(kNode + "/spawn", s) && s.response.success;
  *message = s.response.message;
  return ok;
}

// Up: ~step answers (advertised last).
bool up(const SimClient& sim) {
  return sim.waitUp(60.0) && sim.step(0).success;
}

}  // namespace

TEST(Restart, AfterKillTheNewNodeNamesInheritedValuesAndDropsLeftovers) {
  const std::string dir = "/tmp/ragdoll_restart_" + std::to_string(getpid());
  ASSERT_EQ(system(("mkdir -p " + dir).c_str()), 0);
  SimClient sim(kNode);
  ros::param::del(kNode);  // a clean slate on this master

  const pid_t first = startNode(dir + "/first.log");
  ASSERT_TRUE(up(sim)) << readFile(dir + "/first.log");
  std::map<std::string, double> now;
  ASSERT_TRUE(sim.reconfigure({{{"real_time_factor", 5.0}}, {{"substeps", 8}}, {}}, &now));
  EXPECT_EQ(now["substeps"], 8);
  std::string message;
  ASSERT_TRUE(spawn("ghost", &message)) << message;
  EXPECT_TRUE(ros::param::has("/ghost/robot_description"));
  EXPECT_EQ(stopNode(first, SIGKILL), 128 + SIGKILL);
  // What a crash leaves behind.
  EXPECT_TRUE(ros::param::has("/ghost/robot_description"));
  EXPECT_TRUE(ros::param::has(kNode + "/substeps"));

  const pid_t second = startNode(dir + "/second.log");
  ASSERT_TRUE(up(sim)) << readFile(dir + "/second.log");
  EXPECT_FALSE(ros::param::has("/ghost/robot_description"))
      << "the dead node's ragdoll parameter is deleted";
  EXPECT_FALSE(sim.link("ghost", "pelvis").success) << "no ragdoll 'ghost' in the new node";
  EXPECT_TRUE(sim.reconfigure({}, &now));
  EXPECT_EQ(now["substeps"], 8) << "inherited (and logged)";
  EXPECT_EQ(now["real_time_factor"], 5.0);
  // Spawned again by the new node, then a clean shutdown.
  ASSERT_TRUE(spawn("ghost", &message)) << message;
  ASSERT_TRUE(spawn("kept", &message)) << message;
  EXPECT_TRUE(ros::param::has("/kept/robot_description"));
  EXPECT_EQ(stopNode(second, SIGINT), 0);
  EXPECT_FALSE(ros::param::has("/kept/robot_description")) << "deleted at a clean shutdown";
  EXPECT_FALSE(ros::param::has("/ghost/robot_description"));
  EXPECT_FALSE(ros::param::has(kNode + "/spawned_ragdolls"));

  const std::string log = readFile(dir + "/second.log");
  for (const std::string& words :
       {std::string("~substeps 8 (default 3)"), std::string("~real_time_factor 5 (default 1)"),
        std::string("an earlier node's reconfigured values"),
        std::string("deleted /ghost/robot_description")})
    EXPECT_NE(log.find(words), std::string::npos) << words << " missing from:\n" << log;
  std::printf("[ restart  ] the new node's log:\n%s\n", log.c_str());
  ros::param::del(kNode);
  system(("rm -rf " + dir).c_str());
}

int main(int argc, char** argv) {
  return runRosTests(argc, argv, "restart_test", 1, [] {}, [] {});
}
