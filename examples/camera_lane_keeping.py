#!/usr/bin/env python3
"""Keep the ego in its lane with the front camera only: threshold, bird's-eye warp, fit,
pure pursuit.

An ordinary rospy node for MORAI SIM. It steers from /image_jpeg/compressed alone:

1. decode the JPEG and keep the white and yellow paint (HSV bands);
2. warp the paint to a bird's-eye view of the road with the homography the camera's
   pinhole model gives (640 x 480, 90 deg vertical FOV, mounted 1.2 m above MORAI's
   mount origin, which is the wheel radius above the road);
3. fit a parabola to the paint on each side of the lane centre found in the last frame;
4. steer towards the lane centre LOOKAHEAD_M ahead with pure pursuit, at a constant
   velocity command.

/Ego_topic is read only to report how far from the lane centre the car went
(cross_track_error); it takes no part in the control. Run it with ROS 1, OpenCV
(Debian: python3-opencv), sensor_msgs (python3-sensor-msgs) and morai_msgs on the Python
path (`egosim msgs --export-python DIR`, then PYTHONPATH=DIR):

    egosim run --map loop &
    python3 examples/camera_lane_keeping.py 60     # drive for 60 s of ROS time

It prints the frames it used and the largest distance from the lane centre, then stops
the car.
"""

import math
import sys

import cv2
import numpy as np
import rospy
from morai_msgs.msg import CtrlCmd, EgoVehicleStatus
from sensor_msgs.msg import CompressedImage

WIDTH, HEIGHT = 640, 480
FOCAL_PX = HEIGHT / 2.0  # f = H / (2 tan(90 deg / 2)): MORAI's vertical FOV
CX, CY = (WIDTH - 1) / 2.0, (HEIGHT - 1) / 2.0
WHEEL_RADIUS_M = 0.326  # the default car's; MORAI's mount origin is at axle height
CAMERA_HEIGHT_M = 1.2 + WHEEL_RADIUS_M
CAMERA_AHEAD_OF_AXLE_M = 1.5  # the mount's x: from the rear axle
WHITE = ((0, 0, 185), (30, 60, 255))
YELLOW = ((15, 80, 120), (35, 255, 255))
# Bird's-eye view: the road from NEAR_M to FAR_M ahead, HALF_WIDTH_M each side.
NEAR_M, FAR_M, HALF_WIDTH_M, METRES_PER_PX = 5.0, 30.0, 6.0, 0.05
LANE_WIDTH_M = 3.5
LOOKAHEAD_M = 10.0
SPEED_KMH = 20.0
WHEELBASE_M = 2.7
VELOCITY_MODE = 2
MIN_LINE_PIXELS = 40


def ground_to_image(forward, left):
    """Pixel of a road point `forward` m ahead and `left` m left of the camera."""
    return CX - FOCAL_PX * left / forward, CY + FOCAL_PX * CAMERA_HEIGHT_M / forward


def ground_to_bird(forward, left):
    return (HALF_WIDTH_M - left) / METRES_PER_PX, (FAR_M - forward) / METRES_PER_PX


CORNERS = [
    (NEAR_M, HALF_WIDTH_M),
    (NEAR_M, -HALF_WIDTH_M),
    (FAR_M, -HALF_WIDTH_M),
    (FAR_M, HALF_WIDTH_M),
]
WARP = cv2.getPerspectiveTransform(
    np.float32([ground_to_image(*c) for c in CORNERS]),
    np.float32([ground_to_bird(*c) for c in CORNERS]),
)
BIRD_SIZE = (round(2 * HALF_WIDTH_M / METRES_PER_PX), round((FAR_M - NEAR_M) / METRES_PER_PX))


class LaneKeeper:
    def __init__(self):
        self.centre = np.zeros(3)  # lane centre: left = c0 * forward^2 + c1 * forward + c2
        self.frames = 0
        self.largest_offset = 0.0
        self.command = rospy.Publisher("/ctrl_cmd", CtrlCmd, queue_size=1)
        self.stopped = False

    def on_image(self, message):
        if self.stopped:
            return
        image = cv2.imdecode(np.frombuffer(message.data, np.uint8), cv2.IMREAD_COLOR)
        hsv = cv2.cvtColor(image, cv2.COLOR_BGR2HSV)
        paint = cv2.inRange(hsv, *WHITE) | cv2.inRange(hsv, *YELLOW)
        bird = cv2.warpPerspective(paint, WARP, BIRD_SIZE, flags=cv2.INTER_NEAREST)
        rows, columns = np.nonzero(bird)
        forward = FAR_M - rows * METRES_PER_PX
        left = HALF_WIDTH_M - columns * METRES_PER_PX
        offset = left - np.polyval(self.centre, forward)
        sides = []
        for side in (1.0, -1.0):  # the left line, then the right one
            near = (offset * side > 0.3) & (offset * side < LANE_WIDTH_M - 0.5)
            if np.count_nonzero(near) >= MIN_LINE_PIXELS:
                line = np.polyfit(forward[near], left[near], 2)
                sides.append(line - np.array([0.0, 0.0, side * LANE_WIDTH_M / 2.0]))
        if sides:
            self.centre = np.mean(sides, axis=0)
        self.frames += 1
        self.steer()

    def steer(self):
        ahead = LOOKAHEAD_M + CAMERA_AHEAD_OF_AXLE_M
        lateral = float(np.polyval(self.centre, LOOKAHEAD_M))
        alpha = math.atan2(lateral, ahead)
        steer = math.atan2(2.0 * WHEELBASE_M * math.sin(alpha), math.hypot(ahead, lateral))
        self.command.publish(
            CtrlCmd(longlCmdType=VELOCITY_MODE, velocity=SPEED_KMH, front_steer=steer)
        )

    def on_status(self, status):
        if self.frames > 30:  # once the car is under way
            self.largest_offset = max(self.largest_offset, abs(status.cross_track_error))

    def stop(self):
        self.stopped = True
        self.command.publish(CtrlCmd(longlCmdType=VELOCITY_MODE, velocity=0.0))


def main():
    seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 60.0
    rospy.init_node("camera_lane_keeping")
    keeper = LaneKeeper()
    rospy.Subscriber(
        "/image_jpeg/compressed", CompressedImage, keeper.on_image, queue_size=1, buff_size=2**22
    )
    rospy.Subscriber("/Ego_topic", EgoVehicleStatus, keeper.on_status, queue_size=1)
    rospy.wait_for_message("/image_jpeg/compressed", CompressedImage, timeout=60)
    end = rospy.get_time() + seconds
    while rospy.get_time() < end and not rospy.is_shutdown():
        rospy.sleep(0.1)
    keeper.stop()
    print(
        f"lane keeping done: {keeper.frames} frames, largest distance from the lane centre "
        f"{keeper.largest_offset:.2f} m",
        flush=True,
    )


if __name__ == "__main__":
    main()
