// Validates glTF files with the Khronos glTF-Validator (npm gltf-validator)
// and prints, per file, one line: "<errors> <warnings> <file> <codes of the errors>".
// usage: node tests/cli/gltf_validate.js MODULE_DIR FILE...
// MODULE_DIR is where `npm install gltf-validator` put node_modules.
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require(path.resolve(process.argv[2], 'node_modules', 'gltf-validator'));

async function validate(file) {
    const data = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(data, {
        uri: path.basename(file),
        maxIssues: 0,
        externalResourceFunction: (uri) => new Promise((resolve, reject) => {
            fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (error, bytes) =>
                error ? reject(error.toString()) : resolve(new Uint8Array(bytes)));
        }),
    });
    const errors = report.issues.messages.filter((m) => m.severity === 0).map((m) => m.code);
    return `${report.issues.numErrors} ${report.issues.numWarnings} ${file} ${[...new Set(errors)].sort().join(',')}`;
}

(async () => {
    let status = 0;
    for (const file of process.argv.slice(3)) {
        try {
            console.log(await validate(file));
        } catch (error) {
            console.log(`unreadable 0 ${file} ${String(error).split('\n')[0]}`);
            status = 1;
        }
    }
    process.exit(status);
})();
