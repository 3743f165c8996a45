"""The shell examples of the README and the tutorials, run as written (scripts/run_examples.py).

markdown.py takes the fenced blocks and their commands out of a Markdown file, checks.py decides
whether a command's output is what the document says, session.py runs one document's commands
in a shell of its own against the worlds its lines start.
"""
