#error an older copy one folder deeper: the shallower file wins
