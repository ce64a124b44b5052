"""``vlln data balance``: a built dataset cut down so that scenes and target categories are
evenly represented (the paper's balanced IIGN set), with a report of the counts."""

from vlln.datagen.balance.select import BalanceConfig, Selection, flatness, select
from vlln.datagen.balance.write import balance_dataset

__all__ = ["BalanceConfig", "Selection", "balance_dataset", "flatness", "select"]
