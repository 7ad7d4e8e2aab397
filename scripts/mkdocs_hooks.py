# SPDX-License-Identifier: MIT
"""MkDocs hooks for the docs site (mkdocs.yml): the project's README and CONTRIBUTING, which live
beside docs/, become pages of the site, and the links between them and docs/ are rewritten to the
site's layout, so `mkdocs build --strict` checks every link of the three."""
from pathlib import Path

from mkdocs.structure.files import File

ROOT = Path(__file__).resolve().parent.parent
# Each page brought in from the project root: its name on the site, and its source.
PAGES = {"project-readme.md": ROOT / "README.md", "contributing.md": ROOT / "CONTRIBUTING.md"}


def on_files(files, config):
    for name, source in PAGES.items():
        files.append(File.generated(config, name, content=source.read_text(encoding="utf-8")))
    return files


def on_page_markdown(markdown, page, config, files):
    path = page.file.src_uri
    if path in PAGES:  # a root page: its links into docs/ are the site's own pages
        return markdown.replace("](docs/", "](").replace("](CONTRIBUTING.md)", "](contributing.md)")
    if path == "README.md":  # docs/README.md: its links up to the root pages
        return markdown.replace("](../README.md)", "](project-readme.md)").replace(
            "](../CONTRIBUTING.md)", "](contributing.md)")
    return markdown
