"""The rows that serve the egos: their status out, their command inputs in.

ego.py: EgoVehicleStatus and CtrlCmd; ground_vehicle.py: GVDirectCmd, GVStateCmd and
WeBOT's Twist; ghost.py: GhostMessage (ghost mode's ego input) and NpcGhostCmd;
events.py: MoraiEventCmd (control mode, gear, lamps, pause) and /lamps; multi_ego.py:
MultiEgoSetting and the rows of additional egos; extended_status.py: the extended ego
and object status of 26.r1, with angle_rates.py for the rates they differentiate.
"""
