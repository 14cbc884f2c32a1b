// roscpp subscriber printing "heard <data> from <callerid>" for each message on /chatter.
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <iostream>

void on_message(const ros::MessageEvent<std_msgs::String const>& event) {
  std::cout << "heard " << event.getMessage()->data << " from "
            << event.getPublisherName() << std::endl;
}

int main(int argc, char** argv) {
  ros::init(argc, argv, "cpp_listener");
  ros::NodeHandle node;
  ros::Subscriber sub = node.subscribe("chatter", 100, on_message);
  std::cout << "subscribed" << std::endl;
  ros::spin();
  return 0;
}
