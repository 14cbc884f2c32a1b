"""The exit statuses every egosim command shares (`egosim batch` adds its own)."""

EXIT_OK = 0
EXIT_BAD_INPUT = 2
EXIT_ROS_FAILED = 3
EXIT_STOP_FORCED = 4
"""A clean stop overran its deadline and the process was ended (bag closed); after a
second signal the status is 128 + its number instead, as a shell reports a signal."""
