#!/usr/bin/python3
"""The JSON Schemas of docs/ (issue 31) against the examples, the studies and the readers:

  - both schemas are valid draft 2020-12 schemas;
  - every examples/*.json validates against docs/tsmframe-model.schema.json, every
    studies/*.json against docs/tsmframe-study.schema.json (and its embedded model against the
    model schema);
  - a key "zzz" added to any object of an example or a study (not inside "extra", nor inside a
    study's values or variants, which are model fragments) is refused by the schema, and an
    "extra" of any content added to every object of fixed keys is accepted;
  - drift guard: the key list of every check_keys(...) call in src/tsmframe/io/ and
    src/tsmframe/study/ is the property set (less "extra") of exactly one schema object with
    additionalProperties false, and every such schema object is a reader's key list: a key added
    to a reader and not to the schema (or the other way round) fails here;
  - with the command line given: the reader refuses each "zzz" mutation (exit 2, naming zzz),
    accepts each example with "extra" everywhere (the reader's checks pass: exit 3 from an
    output directory that cannot be made, before any analysis), the values the reader's
    messages list for a bad enumerated value ("(expected …)") are the schema's enum, and values
    out of the reader's ranges (tolerance, divisions, E, nu, ids, ±1e50, …) are refused by both.

    /usr/bin/python3 tests/format/test_schema.py SOURCE_DIR [TSMFRAME_BINARY]

Debian's python3-jsonschema (scripts/setup.sh installs it).
"""
import copy
import glob
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

from jsonschema import Draft202012Validator

SOURCE = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
BINARY = sys.argv[2] if len(sys.argv) > 2 else None

# Keys the schema has before the reader at HEAD does, while another change brings them in:
# tolerated either way (schema location → keys).
PENDING = {}  # schema keys a reader is about to get: {"$defs/x": {"key"}} (none now)


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


MODEL_SCHEMA = load(os.path.join(SOURCE, "docs", "tsmframe-model.schema.json"))
STUDY_SCHEMA = load(os.path.join(SOURCE, "docs", "tsmframe-study.schema.json"))
MODEL = Draft202012Validator(MODEL_SCHEMA)
STUDY = Draft202012Validator(STUDY_SCHEMA)
EXAMPLES = sorted(glob.glob(os.path.join(SOURCE, "examples", "*.json")))
STUDIES = sorted(glob.glob(os.path.join(SOURCE, "studies", "*.json")))


def first_error(validator, document):
    errors = sorted(validator.iter_errors(document), key=lambda e: list(e.absolute_path))
    if not errors:
        return None
    e = errors[0]
    return "/".join(str(p) for p in e.absolute_path) + ": " + e.message[:300]


def objects(document, skip=()):
    """The JSON paths (lists of keys and indices) of every object in `document`, not descending
    into "extra" nor into keys named in `skip`."""
    out = []

    def walk(value, path):
        if isinstance(value, dict):
            out.append(path)
            for k, v in value.items():
                if k != "extra" and k not in skip:
                    walk(v, path + [k])
        elif isinstance(value, list):
            for i, v in enumerate(value):
                walk(v, path + [i])

    walk(document, [])
    return out


def at(document, path):
    for p in path:
        document = document[p]
    return document


def study_objects(study):
    """A study's objects outside its model and its values/variants (model fragments)."""
    return [p for p in objects(study, skip=("model", "values", "set"))]


MAPS = {("units",), ("materials",), ("sections",)}  # a model's objects keyed by names, not fixed keys


def fixed_key_objects(model):
    return [p for p in objects(model) if tuple(p) not in MAPS]


# ---- the readers' key lists ------------------------------------------------------------------

CHECK_KEYS = re.compile(r"check_keys\s*\((?:[^(){};]|\([^()]*\))*?\{([^{}]*)\}\s*\)", re.S)
# for_each_entry(document, "key", {allowed keys}, …): an array's entries checked the same way.
FOR_EACH_ENTRY = re.compile(r"for_each_entry\s*\([^,;]*,\s*\"[^\"]*\",\s*\{([^{}]*)\}", re.S)


def reader_key_lists(folder):
    """(file:line, frozenset of keys) of every check_keys (and for_each_entry) call in src/tsmframe/<folder>/."""
    lists = []
    for path in sorted(glob.glob(os.path.join(SOURCE, "src", "tsmframe", folder, "*.cpp"))):
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for m in [*CHECK_KEYS.finditer(text), *FOR_EACH_ENTRY.finditer(text)]:
            keys = re.findall(r'"([^"]*)"', m.group(1))
            line = text.count("\n", 0, m.start()) + 1
            lists.append((f"{os.path.relpath(path, SOURCE)}:{line}", frozenset(keys)))
    return lists


def schema_objects(schema):
    """(location, frozenset of property names less "extra") of every schema object that allows
    no other keys."""
    out = []

    def walk(node, where):
        if isinstance(node, dict):
            if node.get("additionalProperties") is False and "properties" in node:
                out.append((where, frozenset(node["properties"]) - {"extra"}))
            for k, v in node.items():
                walk(v, f"{where}/{k}" if where else k)
        elif isinstance(node, list):
            for i, v in enumerate(node):
                walk(v, f"{where}/{i}")

    walk(schema, "")
    return out


def matches(location, schema_keys, reader_keys):
    pending = PENDING.get(location, set())
    return schema_keys == reader_keys or schema_keys - pending == reader_keys - pending


class Schemas(unittest.TestCase):
    def test_the_schemas_are_valid(self):
        Draft202012Validator.check_schema(MODEL_SCHEMA)
        Draft202012Validator.check_schema(STUDY_SCHEMA)

    def test_every_example_and_study_validates(self):
        self.assertGreater(len(EXAMPLES), 10)
        self.assertGreater(len(STUDIES), 0)
        for path in EXAMPLES:
            with self.subTest(example=os.path.basename(path)):
                self.assertIsNone(first_error(MODEL, load(path)))
        for path in STUDIES:
            with self.subTest(study=os.path.basename(path)):
                study = load(path)
                self.assertIsNone(first_error(STUDY, study))
                if "model" in study:
                    self.assertIsNone(first_error(MODEL, study["model"]))

    def test_an_unknown_key_is_refused_in_every_object(self):
        for path in EXAMPLES:
            model = load(path)
            for where in objects(model):
                mutated = copy.deepcopy(model)
                at(mutated, where)["zzz"] = 1
                with self.subTest(example=os.path.basename(path), at=where):
                    self.assertFalse(MODEL.is_valid(mutated))
        for path in STUDIES:
            study = load(path)
            for where in study_objects(study):
                mutated = copy.deepcopy(study)
                at(mutated, where)["zzz"] = 1
                with self.subTest(study=os.path.basename(path), at=where):
                    self.assertFalse(STUDY.is_valid(mutated))

    def test_extra_is_allowed_in_every_object_of_fixed_keys(self):
        for path in EXAMPLES:
            model = with_extra_everywhere(load(path))
            with self.subTest(example=os.path.basename(path)):
                self.assertIsNone(first_error(MODEL, model))
        for path in STUDIES:
            study = load(path)
            for where in study_objects(study):
                if where[-1:] != ["set"]:
                    at(study, where)["extra"] = {"note": ["anything", 1, None]}
            with self.subTest(study=os.path.basename(path)):
                self.assertIsNone(first_error(STUDY, study))

    def test_enumerations_refuse_other_strings(self):
        defs = MODEL_SCHEMA["$defs"]
        for where, value in [("dof", "uz"), ("element_kind", "bernoulli")]:
            self.assertFalse(Draft202012Validator(defs[where]).is_valid(value))
        self.assertFalse(MODEL.is_valid({**load(EXAMPLES[0]), "format": "tsmframe-model/2"}))


def with_extra_everywhere(model):
    model = copy.deepcopy(model)
    for where in fixed_key_objects(model):
        at(model, where)["extra"] = {"note": ["anything", 1, None]}
    return model


class DriftGuard(unittest.TestCase):
    """The readers' check_keys lists and the schemas' closed objects are the same sets."""

    def check(self, folder, schema):
        readers = reader_key_lists(folder)
        self.assertGreater(len(readers), 3, f"no check_keys calls found in src/tsmframe/{folder}: has the reader moved?")
        closed = schema_objects(schema)
        for line, keys in readers:
            found = [w for w, s in closed if matches(w, s, keys)]
            with self.subTest(reader=line):
                nearest = max(closed, key=lambda ws: len(ws[1] & keys))
                self.assertEqual(len(found), 1,
                                 f"{line}: check_keys lists {sorted(keys)}; schema objects with exactly these keys: {found}; "
                                 f"nearest {nearest[0]}: missing {sorted(keys - nearest[1])}, not in the reader {sorted(nearest[1] - keys)}")
        for where, keys in closed:
            with self.subTest(schema=where):
                self.assertTrue(any(matches(where, keys, r) for _, r in readers),
                                f"schema object {where} ({sorted(keys)}) is no reader's key list")

    def test_the_model_readers_key_lists_are_the_model_schemas(self):
        self.check("io", MODEL_SCHEMA)

    def test_the_study_readers_key_lists_are_the_study_schemas(self):
        self.check("study", STUDY_SCHEMA)


# ---- against the reader itself ----------------------------------------------------------------

# A bad value at each enumerated place, and the schema enum the reader's message must list:
# (example or study file, JSON path to the object, key, schema $defs path to the enum).
ENUMS = [
    ("examples/portal-frame.json", ["members", 0], "element", "model", ["$defs", "element_kind", "enum"]),
    ("examples/gerber-beam-rolling-contact.json", ["members", 0], "release", "model", ["$defs", "member", "properties", "release", "enum"]),
    ("examples/portal-frame.json", ["supports", 0], "type", "model", ["$defs", "support", "properties", "type", "enum"]),
    ("examples/contact-push.json", ["supports", 1, "fix"], 0, "model", ["$defs", "dof", "enum"]),
    ("examples/portal-frame.json", ["analysis", "control"], "type", "model", ["$defs", "control", "properties", "type", "enum"]),
    ("examples/contact-push.json", ["contacts", 0], "frame", "model", ["$defs", "contact", "properties", "frame", "enum"]),
    ("examples/contact-push.json", ["contacts", 0], "normal", "model", ["$defs", "contact", "properties", "normal", "enum"]),
    ("examples/contact-push.json", ["contacts", 0], "element", "model", ["$defs", "element_kind", "enum"]),
    ("studies/fig7-contact-edge.json", ["record", 0], "quantity", "study", ["$defs", "record", "properties", "quantity", "enum"]),
    ("studies/fig7-contact-edge.json", ["record", 0], "of", "study", ["$defs", "record", "properties", "of", "enum"]),
]


# Values the reader refuses by their range, set in examples/portal-frame.json: (path, key, value).
RANGES = [
    (["analysis"], "tolerance", 1),
    (["analysis"], "tolerance", 0),
    (["analysis"], "max_iterations", 0),
    (["analysis"], "max_cutbacks", 61),
    (["analysis"], "output", 0),
    (["analysis"], "output", 2.5),
    (["analysis", "control"], "steps", 0),
    (["members", 0], "divisions", 0),
    (["members", 0], "divisions", 10000001),
    (["materials", "steel"], "E", 0),
    (["materials", "steel"], "nu", 0.5),
    (["sections", "column"], "I", -1.0),
    (["nodes", 0], "id", 3000000000),
    (["loads", 0], "fx", 1e51),
    (["members", 0], "arc", {"center": [0, 2], "sweep": 0}),
    ([], "format", "tsmframe-model/2"),
]


def expected_list(message):
    """The values in a reader message's "(expected a, b or c)" / "expected \"a\", \"b\" or …"."""
    m = re.search(r"\(expected ([^)]*)\)", message) or re.search(r"expected (.*?)(?: \(|$)", message)
    if not m:
        return None
    return {v.strip().strip('"') for v in re.split(r",\s*|\s+or\s+", m.group(1)) if v.strip()}


@unittest.skipUnless(BINARY, "no tsmframe binary given")
class AgainstTheReader(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        blocker = os.path.join(cls.tmp.name, "a-file")
        open(blocker, "w").close()
        cls.unwritable = os.path.join(blocker, "out")  # under a file: the output cannot be made (exit 3)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def read(self, document, command="run"):
        path = os.path.join(self.tmp.name, "input.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(document, f)
        r = subprocess.run([BINARY, command, path, "--out", self.unwritable, "-q"], capture_output=True, text=True, timeout=60)
        return r.returncode, r.stderr.strip()

    def test_the_reader_refuses_what_the_schema_refuses_for_an_unknown_key(self):
        for path in EXAMPLES:
            model = load(path)
            for where in objects(model):
                mutated = copy.deepcopy(model)
                at(mutated, where)["zzz"] = 1
                code, err = self.read(mutated)
                with self.subTest(example=os.path.basename(path), at=where):
                    self.assertEqual(code, 2, err)
                    self.assertIn("zzz", err)
        for path in STUDIES:
            study = load(path)
            for where in study_objects(study):
                mutated = copy.deepcopy(study)
                at(mutated, where)["zzz"] = 1
                code, err = self.read(mutated, "study")
                with self.subTest(study=os.path.basename(path), at=where):
                    self.assertEqual(code, 2, err)
                    self.assertIn("zzz", err)

    def test_the_reader_accepts_extra_everywhere(self):
        for path in EXAMPLES:
            code, err = self.read(with_extra_everywhere(load(path)))
            with self.subTest(example=os.path.basename(path)):
                self.assertEqual(code, 3, f"expected the reader to accept it (exit 3: no output directory): {err}")

    def test_values_out_of_the_readers_ranges_are_refused_by_both(self):
        for where, key, value in RANGES:
            model = load(os.path.join(SOURCE, "examples", "portal-frame.json"))
            at(model, where)[key] = value
            code, err = self.read(model)
            with self.subTest(at=where + [key], value=value):
                self.assertEqual(code, 2, err)
                self.assertFalse(MODEL.is_valid(model))

    def test_the_readers_enumerations_are_the_schemas(self):
        for file, where, key, which, enum_at in ENUMS:
            document = load(os.path.join(SOURCE, file))
            schema = MODEL_SCHEMA if which == "model" else STUDY_SCHEMA
            enum = set(at(schema, enum_at))
            mutated = copy.deepcopy(document)
            if which == "study":
                mutated["record"] = [{"name": "peak", "quantity": "load_factor", "of": "max"}]
            at(mutated, where)[key] = "zzz"
            code, err = self.read(mutated, "run" if which == "model" else "study")
            with self.subTest(file=file, at=where + [key]):
                self.assertEqual(code, 2, err)
                self.assertEqual(expected_list(err), enum, err)
                self.assertFalse((MODEL if which == "model" else STUDY).is_valid(mutated))
                for value in enum:
                    at(mutated, where)[key] = value
                    self.assertTrue(Draft202012Validator(at(schema, enum_at[:-1])).is_valid(value))


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"] if "-v" in sys.argv else [sys.argv[0]])
