#!/usr/bin/env python3
"""No include runs back up the layers: the model (common/) includes no
program folder, and the master and the worker include nothing of the
`animat` command line (cli/) or of each other's folders. Prints each
include that does and exits 1, or says how many files it read and exits 0.

    scripts/include_layers.py [ROOT]
"""

import os
import re
import sys

# Folder -> the folders its files may not include from.
FORBIDDEN = {
    'common': ['analysis', 'figures', 'viz', 'cli', 'master', 'worker',
               'bench', 'tests'],
    'master': ['cli', 'worker', 'bench', 'tests'],
    'worker': ['cli', 'master', 'bench', 'tests'],
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def violations(root):
    """Yields (path, line number, included path) of each backward include,
    and counts the files read in `violations.files`."""
    violations.files = 0
    for folder, banned in sorted(FORBIDDEN.items()):
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, folder)):
            dirnames.sort()
            for name in sorted(filenames):
                if not name.endswith(('.h', '.cc')):
                    continue
                path = os.path.join(dirpath, name)
                violations.files += 1
                with open(path, encoding='utf-8') as f:
                    for number, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if m and m.group(1).split('/')[0] in banned:
                            yield os.path.relpath(path, root), number, m.group(1)


def main(argv):
    root = argv[1] if len(argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), '..')
    found = list(violations(root))
    for path, number, included in found:
        print(f'{path}:{number}: includes "{included}", a layer above it')
    if found:
        return 1
    print(f'include layers: {violations.files} files, no include runs back up')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
