// Validates each Kubernetes object in the given YAML files against the full upstream
// OpenAPI schemas as packaged by the npm module kubernetes-models (types, formats, enums,
// required fields; it does not reject unknown fields, which check.py does).
// Run by deploy/check-manifests.sh from a directory where kubernetes-models and js-yaml
// are installed.
import fs from "node:fs";
import yaml from "js-yaml";

let errors = 0;
let checked = 0;
for (const file of process.argv.slice(2)) {
  for (const doc of yaml.loadAll(fs.readFileSync(file, "utf8"))) {
    if (!doc || !doc.apiVersion || doc.apiVersion.startsWith("kustomize.")) continue;
    const [group, version] = doc.apiVersion.includes("/")
      ? doc.apiVersion.split("/") : [null, doc.apiVersion];
    const mod = `kubernetes-models/${group ? group + "/" : ""}${version}/${doc.kind}`;
    let Model;
    try {
      Model = (await import(mod))[doc.kind];
    } catch (e) {
      console.log(`error: ${file}: no upstream model for ${doc.apiVersion} ${doc.kind}`);
      errors++;
      continue;
    }
    try {
      new Model(doc).validate();
      checked++;
    } catch (e) {
      console.log(`error: ${file} ${doc.kind}/${doc.metadata?.name}: ${e.message}`);
      errors++;
    }
  }
}
console.log(`upstream schemas: ${checked} objects valid, ${errors} errors`);
process.exit(errors ? 1 : 0);
