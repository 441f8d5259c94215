"""The main job's watch over its pipeline: a progress line per stage, and the errors and warnings each stage reports,
caught as VTK events on the stage's algorithm and executive (so that a failed stage stops the job with one line,
instead of its output being passed on, and VTK's multi-line messages are not printed)."""
import re
import signal
import sys
import time

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING


class StageError(Exception):
    """A stage of the pipeline reported an error (one line: the stage, then what it said)."""


class Interrupted(Exception):
    """The user pressed Ctrl-C (SIGINT) or sent SIGTERM: the running stage was told to stop."""


def eta(elapsed, fraction):
    """'about N s left' from the time a stage has taken and the fraction it has done ('' too early to say)."""
    if fraction <= 0.02 or elapsed < 1.0 or fraction >= 1.0:
        return ''
    left = elapsed * (1.0 - fraction) / fraction
    return ', about %s left' % (('%.0f s' % left) if left < 120 else ('%.1f min' % (left / 60.0)))


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
        self.started = {}    # label -> time of its first progress event
        self.algorithms = []  # every watched algorithm, told to stop on an interruption
        self.interrupted = False
        self.in_pipeline = False

    def handle_interruptions(self):
        """Ctrl-C (SIGINT) and SIGTERM: while a pipeline update runs, every watched algorithm is told to stop
        (AbortExecute: the GLS filters check it at each progress step, so within about a second) and check() then
        raises Interrupted; elsewhere Interrupted is raised at once. Python's own handler cannot serve: inside a
        VTK observer, VTK ends the process on a KeyboardInterrupt, before the staged files can be removed."""
        def on_signal(_signum, _frame):
            self.interrupted = True
            if not self.in_pipeline:
                raise Interrupted()
            for algorithm in self.algorithms:
                algorithm.SetAbortExecute(1)
        signal.signal(signal.SIGINT, on_signal)
        signal.signal(signal.SIGTERM, on_signal)

    def update(self, proxy):
        """proxy.UpdatePipeline() with the interruption armed, then check()."""
        self.in_pipeline = True
        try:
            proxy.UpdatePipeline()
        finally:
            self.in_pipeline = False
        self.check()

    def watch(self, proxy, label, progress=True):
        algorithm = proxy.GetClientSideObject()
        self.algorithms.append(algorithm)
        # A progress observer runs Python code during the update, where a pending signal is handled.
        algorithm.AddObserver('ProgressEvent', self._on_progress(label) if progress else (lambda *_: None))
        # ParaView's readers are often a vtkFileSeriesReader around the reader that reports the errors.
        inner = algorithm.GetReader() if hasattr(algorithm, 'GetReader') else None
        for target in (algorithm, inner):
            if target is not None:
                target.AddObserver('ErrorEvent', self._on_message(label, self.errors.append))
                target.AddObserver('WarningEvent', self._on_message(label, self._print_warning))
                target.GetExecutive().AddObserver('ErrorEvent', self._on_message(label, self._note_failure))
        return proxy

    def check(self):
        """Raises Interrupted after Ctrl-C, StageError if a watched stage reported an error since the last check."""
        if self.interrupted:
            raise Interrupted()
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
            fraction = obj.GetProgress()
            now = time.time()
            start = self.started.setdefault(label, now)
            step = int(fraction * (100 if self.tty else 4))
            if (label, step) == self.last:
                return
            self.last = (label, step)
            text = '  %-24s %3.0f%% (%.0f s%s)' % (label, 100.0 * fraction, now - start, eta(now - start, fraction))
            if self.tty:
                sys.stderr.write('\r%-72s%s' % (text, '\n' if fraction >= 1.0 else ''))
            else:
                sys.stderr.write(text + '\n')
            sys.stderr.flush()
        return report
