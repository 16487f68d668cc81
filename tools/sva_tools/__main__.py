import sys

try:
    from .commands import main

    sys.exit(main())
except KeyboardInterrupt:  # before a command could take it (while starting up)
    print("sva-tools: interrupted", file=sys.stderr)
    sys.exit(130)
