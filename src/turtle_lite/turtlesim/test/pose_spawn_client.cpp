// A C++ client of the kind the course writes (MoveTurtle.cpp): it includes turtlesim's generated
// headers, spawns a turtle through turtlesim/Spawn, drives it and prints the poses it receives.
// The integration test runs it against the workspace's simulator.
// Usage: pose_spawn_client NAME   exits 0 once NAME has moved, 1 on any failure.
#include <cstdio>
#include <string>

#include "geometry_msgs/Twist.h"
#include "ros/ros.h"
#include "turtlesim/Pose.h"
#include "turtlesim/Spawn.h"

namespace {
const double START_X = 2.0;
const double START_Y = 3.0;
const double MOVED_M = 0.1;  // distance from the spawn point that counts as "moved"
const int MAX_WAIT_CYCLES = 300;  // 30 s at 10 Hz: the test's own deadline is shorter

turtlesim::Pose last_pose;
int poses_received = 0;

void poseCallback(const turtlesim::PoseConstPtr& msg) {
  last_pose = *msg;
  ++poses_received;
}
}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "pose_spawn_client");
  if (argc < 2) {
    ROS_ERROR("usage: pose_spawn_client NAME");
    return 1;
  }
  const std::string name = argv[1];
  ros::NodeHandle node;

  if (!ros::service::waitForService("spawn", ros::Duration(10.0))) {
    ROS_ERROR("no spawn service");
    return 1;
  }
  turtlesim::Spawn spawn;
  spawn.request.x = START_X;
  spawn.request.y = START_Y;
  spawn.request.theta = 0.0;
  spawn.request.name = name;
  if (!ros::service::call("spawn", spawn) || spawn.response.name != name) {
    ROS_ERROR("spawn failed");
    return 1;
  }
  ROS_INFO("spawned %s", spawn.response.name.c_str());

  ros::Publisher pub = node.advertise<geometry_msgs::Twist>(name + "/cmd_vel", 10);
  ros::Subscriber sub = node.subscribe(name + "/pose", 10, poseCallback);
  geometry_msgs::Twist forward;
  forward.linear.x = 1.0;

  ros::Rate rate(10);
  for (int cycle = 0; cycle < MAX_WAIT_CYCLES && ros::ok(); ++cycle) {
    pub.publish(forward);
    ros::spinOnce();
    if (poses_received > 0 && last_pose.x > START_X + MOVED_M) {
      std::printf("pose x: %.2f, y: %.2f, theta: %.2f\n", last_pose.x, last_pose.y, last_pose.theta);
      std::fflush(stdout);
      return 0;
    }
    rate.sleep();
  }
  ROS_ERROR("%s did not move (%d poses received)", name.c_str(), poses_received);
  return 1;
}
