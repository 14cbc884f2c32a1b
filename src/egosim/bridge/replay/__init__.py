"""Rosbag replay on the wire (the replay engine itself is egosim.replay).

replay_rows.py: /Morai_SimProc, MoraiSimProcStatus, ReplayInfo and the replay stage of
a tick; replayed_scene.py: a replayed frame as the world's records.
"""
