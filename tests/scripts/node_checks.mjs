// SPDX-License-Identifier: MIT
// node_checks.mjs -- what the node checks share: failing with the check's
// name, waiting for a condition with a deadline, and a limit on the whole run.

/// The helpers of the check `name`; the process exits 1 with `name: what`
/// on a failed check and after `limitSeconds` in all.
export function checks(name, limitSeconds) {
  const fail = (what) => {
    console.error(name + ": " + what);
    process.exit(1);
  };
  const need = (ok, what) => ok || fail(what);
  const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
  async function until(condition, seconds, what) {
    for (const end = Date.now() + seconds * 1000; !condition(); await sleep(50)) {
      if (Date.now() > end) fail("timed out waiting for " + what);
    }
  }
  setTimeout(() => fail(`the whole check took more than ${limitSeconds} s`), limitSeconds * 1000).unref();
  return { fail, need, sleep, until };
}
