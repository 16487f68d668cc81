"""Run by the test venv's Python (where only the installed wheel provides `sva`): reads
a JSON list of calls on stdin, answers a JSON list of results on stdout.

A call: {"kind": "plan" | "plan_dict" | "replan", "path": FILE, "algo": NAME,
"source": NAME}. A result: {"text": PLAN_TEXT} or {"error": CLASS, "message": MESSAGE}.
"""
import json
import sys

import sva


def call(request: dict) -> dict:
    with open(request["path"], "rb") as file:
        data = file.read()
    try:
        if request["kind"] == "plan":
            text = sva.plan_text(data, request["algo"], source=request["source"])
        elif request["kind"] == "plan_dict":
            mission = json.loads(data)
            plan = sva.plan(mission, request["algo"])
            text = json.dumps(plan)
        else:
            text = sva.replan_text(json.loads(data), request["algo"], source=request["source"])
    except sva.Error as error:
        return {"error": type(error).__name__, "message": error.message}
    return {"text": text}


def main() -> None:
    requests = json.load(sys.stdin)
    json.dump([call(request) for request in requests], sys.stdout)


if __name__ == "__main__":
    main()
