// The run summary panel, from run.json.

const fmtSeconds = (s) => (s >= 60 ? `${Math.floor(s / 60)} min ${(s % 60).toFixed(0)} s` : `${s.toPrecision(3)} s`);

export function showSummary(run, frames) {
  const rows = [
    ['status', run.status + (run.stopped_by ? ` (${run.stopped_by})` : '')],
    ['steps', run.steps_total ? `${run.steps} / ${run.steps_total} (${((100 * run.steps) / run.steps_total).toFixed(0)}%)` : run.steps],
    ['simulated', run.simulated_time !== undefined ? `${run.simulated_time.toPrecision(4)} s` : undefined],
    ['wall time', run.wall_time_s !== undefined ? fmtSeconds(run.wall_time_s) : undefined],
    ['bodies', run.bodies],
    ['templates', run.shape_templates],
    ['dt', run.dt !== undefined ? `${Number(run.dt).toPrecision(4)} s` : undefined],
    ['threads', run.threads],
    ['frames', frames],
    ['version', run.version],
  ].filter(([, v]) => v !== undefined);
  const summary = document.getElementById('summary');
  summary.replaceChildren(...rows.flatMap(([k, v]) => [Object.assign(document.createElement('dt'), { textContent: k }), Object.assign(document.createElement('dd'), { textContent: String(v) })]));
  document.getElementById('warnings').replaceChildren(...(run.warnings ?? []).map((w) => Object.assign(document.createElement('li'), { textContent: w })));
  const error = document.getElementById('error');
  error.hidden = !run.error;
  error.textContent = run.error ? `error: ${run.error}` : '';
}
