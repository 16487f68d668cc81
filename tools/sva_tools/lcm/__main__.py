import sys

from ..commands.lcm import main

sys.exit(main(sys.argv[1:]))
