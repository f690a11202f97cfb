"""Outside mechanisms, SEALED half (issue 31 part 4): its mechanisms and rows follow in the next commit."""
FORM_CLASSES = ()


def suite_rows():
    """The sealed suite's rows (none yet)."""
    return []
