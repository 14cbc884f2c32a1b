// roscpp publisher of std_msgs/String "cpp <i>" on /chatter at 20 Hz until killed.
#include <ros/ros.h>
#include <std_msgs/String.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "cpp_talker");
  ros::NodeHandle node;
  ros::Publisher pub = node.advertise<std_msgs::String>("chatter", 100);
  ros::Rate rate(20);
  for (int i = 0; ros::ok(); ++i) {
    std_msgs::String message;
    message.data = "cpp " + std::to_string(i);
    pub.publish(message);
    ros::spinOnce();
    rate.sleep();
  }
  return 0;
}
