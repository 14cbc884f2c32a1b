from egosim.ros1.graph import nodes_of


def test_system_state_becomes_one_entry_per_node() -> None:
    state = (
        [["/Ego_topic", ["/egosim"]], ["/ctrl_cmd", ["/driver", "/teleop"]]],
        [["/ctrl_cmd", ["/egosim"]], ["/Ego_topic", ["/driver"]]],
        [["/Service_MoraiEventCmd", ["/egosim"]]],
    )
    assert nodes_of(state) == [
        {
            "name": "/driver",
            "publishes": ["/ctrl_cmd"],
            "subscribes": ["/Ego_topic"],
            "services": [],
        },
        {
            "name": "/egosim",
            "publishes": ["/Ego_topic"],
            "subscribes": ["/ctrl_cmd"],
            "services": ["/Service_MoraiEventCmd"],
        },
        {"name": "/teleop", "publishes": ["/ctrl_cmd"], "subscribes": [], "services": []},
    ]
