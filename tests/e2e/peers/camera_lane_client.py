"""A rospy node reading /image_jpeg/compressed the way MORAI lane-keeping code does
(run by /usr/bin/python3 with Debian's python3-opencv).

argv: TOPIC DEFINITION_FILE CAMERA_HEIGHT_M
Decodes one frame with cv2.imdecode, thresholds white and yellow paint in HSV (the
bands MORAI examples use), and maps the paint pixels of the lower image to the ground
with the pinhole model of the frame's size (vertical FOV 90 deg). Prints one JSON line:
the frame's format, frame_id and size, and the median lateral offset (m, left positive)
of the yellow paint left of the camera and of the white paint right of it.
"""

import json
import sys

import cv2
import genpy.dynamic
import numpy as np
import rospy

TOPIC, HEIGHT = sys.argv[1], float(sys.argv[3])
with open(sys.argv[2]) as definition_file:
    DEFINITION = definition_file.read()
WHITE = ((0, 0, 185), (30, 60, 255))
YELLOW = ((15, 80, 120), (35, 255, 255))

CompressedImage = genpy.dynamic.generate_dynamic("sensor_msgs/CompressedImage", DEFINITION)[
    "sensor_msgs/CompressedImage"
]


def laterals(mask, f, cx, cy):
    rows, columns = np.nonzero(mask)
    below = rows > cy + 10  # the road up to about 36 m ahead
    rows, columns = rows[below], columns[below]
    return -(columns - cx) * HEIGHT / (rows - cy)


def main():
    rospy.init_node("camera_lane_client", anonymous=True)
    message = rospy.wait_for_message(TOPIC, CompressedImage, timeout=60)
    image = cv2.imdecode(np.frombuffer(message.data, np.uint8), cv2.IMREAD_COLOR)
    height, width = image.shape[:2]
    f = height / 2.0  # vertical FOV 90 deg: f = H / (2 tan 45 deg)
    cx, cy = (width - 1) / 2.0, (height - 1) / 2.0
    hsv = cv2.cvtColor(image, cv2.COLOR_BGR2HSV)
    yellow = laterals(cv2.inRange(hsv, *YELLOW), f, cx, cy)
    white = laterals(cv2.inRange(hsv, *WHITE), f, cx, cy)
    left = yellow[(yellow > 0) & (yellow < 3)]
    right = white[(white < 0) & (white > -3)]
    print(
        json.dumps(
            {
                "format": message.format,
                "frame_id": message.header.frame_id,
                "size": [width, height],
                "left_m": float(np.median(left)) if len(left) else None,
                "right_m": float(np.median(right)) if len(right) else None,
                "left_pixels": len(left),
                "right_pixels": len(right),
            }
        ),
        flush=True,
    )


if __name__ == "__main__":
    main()
