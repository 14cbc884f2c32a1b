"""MORAI SIM's own scenario files: the JSON documents its scenario editor saves.

Public API:
    read_morai_scenario(text, label) -> MoraiScenario   the Scenario and what was not done
    morai_document(text, label) -> dict                 the file's JSON object, unread
    unity_to_enu, heading_of                            MORAI's axes and angles -> egosim's
"""

from egosim.world.scenario.morai.reader import MoraiScenario, morai_document, read_morai_scenario
from egosim.world.scenario.morai.units import heading_of, unity_to_enu

__all__ = ["MoraiScenario", "heading_of", "morai_document", "read_morai_scenario", "unity_to_enu"]
