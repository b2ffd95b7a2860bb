"""rqt_plot's window: a pyqtgraph time plot of the series a PlotSource keeps.

Rules: the window redraws at a fixed frame rate (FPS) from copies of the series, each thinned to
the visible time range and to a minimum and maximum per pixel column (PlotSource.peaks), so
neither the message rate nor the history sets the amount of drawing; a tick with nothing new
(same data, same view) draws nothing, nor does a plot that cannot be seen (hidden, or a dock
tabbed behind another). Autoscroll keeps the newest `history` seconds in view;
"Y auto" fits the value axis to what is drawn (the window's own range, from the thinned points,
not pyqtgraph's auto-range, which measures every curve again on each change). Dragging or
zooming an axis with the mouse turns its automatic range off. Pausing freezes the picture while
data keeps arriving. Series are added with completion of the published numeric fields and
removed from a menu.
"""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt, QTimer
from PySide6.QtGui import QCloseEvent
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QCompleter,
    QDoubleSpinBox,
    QLabel,
    QLineEdit,
    QPushButton,
    QVBoxLayout,
    QWidget,
)

from kame.node.master_proxy import MasterError
from kame.rqt.flow_layout import FlowLayout
from kame.rqt.plot_model import SeriesNameError, expand_series_args, padded, value_range
from kame.rqt.plot_source import PlotSource

FPS = 33  # a little above the 30 a smooth plot needs: a late tick (a busy machine) then costs no frame below it
PADDING = 0.02  # of each axis' span, on both sides
COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22",
           "#17becf")


class PlotWindow(QWidget):
    def __init__(self, source: PlotSource) -> None:
        super().__init__()
        self.setWindowTitle("rqt_plot")
        self.source = source
        pg.setConfigOptions(antialias=False, background="w", foreground="k")
        self.plot = pg.PlotWidget()
        self.plot.setLabel("bottom", "time", units="s")
        # An axis with an automatic SI prefix lays its label out again on each change of range: every
        # frame for the time axis, and the hidden top and right axes follow the view as well.
        # Seconds stay seconds.
        for side in ("bottom", "top", "right"):
            self.plot.getAxis(side).enableAutoSIPrefix(False)
        self.plot.disableAutoRange()  # the window sets both ranges itself (redraw)
        self.plot.hideButtons()  # pyqtgraph's own auto-range button would fight the window's
        self.legend = self.plot.addLegend()
        self.curves: dict[str, pg.PlotCurveItem] = {}
        self._drawn: tuple[object, ...] | None = None  # what the last frame showed

        self.topic = QLineEdit()
        self.topic.setPlaceholderText("/topic/field (x:y for several)")
        self.completer = QCompleter([])
        self.completer.setCaseSensitivity(Qt.CaseSensitivity.CaseInsensitive)
        self.completer.setFilterMode(Qt.MatchFlag.MatchContains)
        self.topic.setCompleter(self.completer)
        self.add_button = QPushButton("+")
        self.remove_box = QComboBox()
        self.remove_button = QPushButton("-")
        self.pause_button = QPushButton("Pause")
        self.pause_button.setCheckable(True)
        self.clear_button = QPushButton("Clear")
        self.autoscroll = QCheckBox("Autoscroll")
        self.autoscroll.setChecked(True)
        self.history = QDoubleSpinBox()
        self.history.setRange(1, 3600)
        self.history.setValue(source.history)
        self.history.setSuffix(" s")
        self.y_auto = QCheckBox("Y auto")
        self.y_auto.setChecked(True)
        self.y_min = QDoubleSpinBox()
        self.y_max = QDoubleSpinBox()
        for box, value in ((self.y_min, -1.0), (self.y_max, 12.0)):
            box.setRange(-1e9, 1e9)
            box.setDecimals(3)
            box.setValue(value)
        self.status = QLabel("")

        # rows that wrap, so a narrow dock keeps every control on screen
        top = FlowLayout()
        self.topic.setMinimumWidth(220)
        top.add_widgets(QLabel("Topic"), self.topic, self.add_button, self.remove_box, self.remove_button,
                        self.pause_button, self.clear_button)
        axes = FlowLayout()
        axes.add_widgets(self.autoscroll, QLabel("history"), self.history, self.y_auto, QLabel("y from"), self.y_min,
                         QLabel("to"), self.y_max, self.status)
        page = QVBoxLayout(self)
        page.addLayout(top)
        page.addWidget(self.plot, 1)
        page.addLayout(axes)
        self.resize(900, 560)

        self.add_button.clicked.connect(lambda: self.add_series(self.topic.text()))
        self.topic.returnPressed.connect(lambda: self.add_series(self.topic.text()))
        self.remove_button.clicked.connect(lambda: self.remove_series(self.remove_box.currentText()))
        self.clear_button.clicked.connect(self.source.clear)
        self.history.valueChanged.connect(self.source.set_history)
        self.y_auto.toggled.connect(self._apply_y_range)
        self.y_min.valueChanged.connect(self._apply_y_range)
        self.y_max.valueChanged.connect(self._apply_y_range)
        self.pause_button.toggled.connect(lambda on: self.pause_button.setText("Resume" if on else "Pause"))
        self.autoscroll.toggled.connect(self._forget_frame)
        self.plot.getViewBox().sigRangeChangedManually.connect(self._taken_by_mouse)
        self.timer = QTimer(self)
        self.timer.timeout.connect(self.redraw)
        self.timer.setTimerType(Qt.TimerType.PreciseTimer)  # a coarse timer may run 5% late
        self.timer.start(1000 // FPS)

    def refresh_completions(self) -> None:
        try:
            names = self.source.completions()
        except (OSError, MasterError) as exc:
            self.status.setText(f"cannot list topics: {exc}")
            return
        self.completer.model().setStringList(names)  # type: ignore[attr-defined]

    def add_series(self, text: str) -> list[str]:
        """Add every series `text` names; returns the ones added (errors go to the status line)."""
        added = []
        problems = []
        for name in expand_series_args([text]):
            try:
                self.source.add(name)
            except (SeriesNameError, OSError, MasterError) as exc:
                problems.append(str(exc))
                continue
            if name not in self.curves:
                colour = COLOURS[len(self.curves) % len(COLOURS)]
                curve = pg.PlotCurveItem(name=name, pen=pg.mkPen(colour, width=1))
                self.curves[name] = curve
                self.plot.addItem(curve)
                self.remove_box.addItem(name)
                added.append(name)
        self.status.setText("; ".join(problems))
        if added:
            self.topic.clear()
        return added

    def remove_series(self, name: str) -> None:
        curve = self.curves.pop(name, None)
        if curve is None:
            return
        self.source.remove(name)
        self.plot.removeItem(curve)
        self.legend.removeItem(curve)
        self.remove_box.removeItem(self.remove_box.findText(name))

    def _apply_y_range(self) -> None:
        if self.y_auto.isChecked():
            self._forget_frame()
        else:
            self.plot.setYRange(self.y_min.value(), self.y_max.value(), padding=0)

    def _forget_frame(self) -> None:
        """The next tick draws even if the data did not change (an axis mode changed)."""
        self._drawn = None

    def _taken_by_mouse(self, axes: list[bool]) -> None:
        """The user dragged or zoomed: the axes they moved stop following the data."""
        if axes[0]:
            self.autoscroll.setChecked(False)
        if axes[1] and self.y_auto.isChecked():
            low, high = self.plot.getViewBox().viewRange()[1]
            self.y_auto.setChecked(False)
            self.y_min.setValue(low)
            self.y_max.setValue(high)

    def redraw(self) -> None:
        """One frame: the visible points of each series, thinned to the pixel columns, and the
        axes that follow the data; nothing when neither the data nor the view changed."""
        if self.pause_button.isChecked() or self.visibleRegion().isEmpty():  # paused, hidden or tabbed away
            return
        view = self.plot.getViewBox()
        (start, end), _ = view.viewRange()
        scrolling = self.autoscroll.isChecked()
        if scrolling:
            newest = self.source.newest()
            if newest is not None:
                start, end = padded(max(0.0, newest - self.source.history), max(newest, 1.0), PADDING)
        bins = max(int(view.width()), 100)
        frame = (self.source.version, start, end, bins)
        if frame == self._drawn:
            return
        self._drawn = frame
        peaks = self.source.peaks(start, end, bins)
        for name, (t, v) in peaks.items():
            curve = self.curves.get(name)
            if curve is not None:
                finite = bool(np.isfinite(v).all())  # else pyqtgraph must find the gaps (NaN, inf)
                curve.setData(t, v, connect="all" if finite else "finite", skipFiniteCheck=finite)
        y_range = value_range(v for _, v in peaks.values()) if self.y_auto.isChecked() else None
        if scrolling or y_range is not None:
            view.setRange(xRange=(start, end) if scrolling else None, yRange=y_range, padding=0)
        # pyqtgraph moves the view's contents lazily, when a paint begins; moving them then makes
        # Qt paint the whole plot a second time. Moved now, both changes go in one paint.
        self.plot.scene().prepareForPaint()
        errors = self.source.problems()
        if errors:
            self.status.setText(errors[-1])

    def closeEvent(self, event: QCloseEvent) -> None:
        self.timer.stop()
        super().closeEvent(event)
