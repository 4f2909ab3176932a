"""The command line every layout checker shares:

  CHECKER [ROOT]        check the tree at ROOT (default: the repository root)
  CHECKER --self-test   check that the checker catches what it plants

Exit status: 0 clean, 1 findings (one line each), 2 usage."""
import os
import sys


def run(argv, usage, check, self_test, clean):
    """check(root) -> list of findings; self_test() -> exit status; clean(root)
    -> the line printed when there is nothing to report."""
    if len(argv) > 2:
        print(usage)
        return 2
    if len(argv) == 2 and argv[1] == "--self-test":
        return self_test()
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.abspath(argv[1] if len(argv) == 2 else os.path.join(here, "..", ".."))
    findings = check(root)
    for f in findings:
        print(f)
    if findings:
        return 1
    print(clean(root))
    return 0
