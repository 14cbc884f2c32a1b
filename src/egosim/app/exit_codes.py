"""The exit statuses every egosim command shares (`egosim batch` adds its own)."""

EXIT_OK = 0
EXIT_BAD_INPUT = 2
EXIT_ROS_FAILED = 3
