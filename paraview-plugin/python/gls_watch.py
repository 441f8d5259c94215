"""The main job's watch over its pipeline: a progress line per stage, and the errors and warnings each stage reports,
caught as VTK events on the stage's algorithm and executive (so that a failed stage stops the job with one line,
instead of its output being passed on, and VTK's multi-line messages are not printed)."""
import re
import sys

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING


class StageError(Exception):
    """A stage of the pipeline reported an error (one line: the stage, then what it said)."""


def one_line(message):
    """The text of a VTK error or warning event without its "ERROR: In file, line N" line, the object's
    "vtkClass (0x...): " prefix and a final full stop, on one line."""
    lines = [line.strip() for line in message.strip().splitlines() if line.strip()]
    if lines and re.match(r'^(ERROR|Warning|Generic Warning): In ', lines[0]):
        lines = lines[1:]
    text = ' '.join(lines)
    return re.sub(r'^\w+ \(0x[0-9a-fA-F]+\): ', '', text).rstrip('.')


class Watch:
    """Attach with watch(proxy, label) before the proxy updates; check() raises StageError for the first error."""

    def __init__(self):
        self.tty = sys.stderr.isatty()
        self.last = None
        self.errors = []     # (label, message) from the algorithms
        self.failures = []   # labels whose executive reported a failed request without an algorithm message

    def watch(self, proxy, label, progress=True):
        algorithm = proxy.GetClientSideObject()
        if progress:
            algorithm.AddObserver('ProgressEvent', self._on_progress(label))
        # ParaView's readers are often a vtkFileSeriesReader around the reader that reports the errors.
        inner = algorithm.GetReader() if hasattr(algorithm, 'GetReader') else None
        for target in (algorithm, inner):
            if target is not None:
                target.AddObserver('ErrorEvent', self._on_message(label, self.errors.append))
                target.AddObserver('WarningEvent', self._on_message(label, self._print_warning))
                target.GetExecutive().AddObserver('ErrorEvent', self._on_message(label, self._note_failure))
        return proxy

    def check(self):
        """Raises StageError if a watched stage reported an error since the last check."""
        errors, failures = self.errors, self.failures
        self.errors, self.failures = [], []
        if errors:
            raise StageError('%s: %s' % errors[0])
        if failures:
            raise StageError('%s failed (see the messages above)' % failures[0])

    @staticmethod
    def _on_message(label, sink):
        @calldata_type(VTK_STRING)
        def on_message(_obj, _event, message):
            sink((label, one_line(message or '')))
        return on_message

    @staticmethod
    def _print_warning(item):
        print('gls-analyze: warning: %s: %s' % item, file=sys.stderr)

    def _note_failure(self, item):
        self.failures.append(item[0])

    def _on_progress(self, label):
        def report(obj, _event):
            step = int(obj.GetProgress() * (100 if self.tty else 4))
            if (label, step) == self.last:
                return
            self.last = (label, step)
            pct = 100.0 * obj.GetProgress()
            if self.tty:
                sys.stderr.write('\r  %-24s %3.0f%%%s' % (label, pct, '\n' if pct >= 100 else ''))
            else:
                sys.stderr.write('  %-24s %3.0f%%\n' % (label, pct))
            sys.stderr.flush()
        return report
