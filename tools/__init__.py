"""The project's Python tools (installable: pyproject.toml at the repository root; tools/bootstrap.sh
installs it editable into .venv)."""
