"""The shared ant-colony engine: problem view, pheromone trails, walk rules, compiled walks and the colony loop."""

from pathzoo_aco.engine.colony import AntColonyPlanner, ColonyState, colony_params
from pathzoo_aco.engine.pheromone import Pheromone, deposit_walks
from pathzoo_aco.engine.problem import ColonyProblem
from pathzoo_aco.engine.rules import EMPTY, WalkRules
from pathzoo_aco.engine.walk import ABORTED, EXHAUSTED, OUTRUN, REACHED, STEP_CAP, STUCK, WalkEngine
from pathzoo_aco.engine.walk_result import Walks

__all__ = [
    "ABORTED",
    "AntColonyPlanner",
    "ColonyProblem",
    "ColonyState",
    "EMPTY",
    "EXHAUSTED",
    "OUTRUN",
    "Pheromone",
    "REACHED",
    "STEP_CAP",
    "STUCK",
    "WalkEngine",
    "WalkRules",
    "Walks",
    "colony_params",
    "deposit_walks",
]
