"""The recent answers of a costly function of images, found again by a hash of their pixels.

The lessons and the command line ask about the same photos more than once: lesson 08
detects the chessboards of photos it detected before, and lesson 09 stitches the same
photos at several settings, each stitch detecting their features again. A detector wrapped
in :class:`RecentAnswers` answers a photo it has seen (the same pixels and the same
settings) from memory. The caller returns a copy, so that a student who changes the answer
does not change what the next call gets.
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from collections.abc import Callable, Hashable, Sequence
from typing import Generic, TypeVar

import numpy as np

Answer = TypeVar("Answer")


def pixels_key(pixels: np.ndarray | None) -> tuple | None:
    """What identifies an array's contents: a 16-byte hash of its bytes, its shape and dtype."""
    if pixels is None:
        return None
    data = np.ascontiguousarray(pixels)
    return hashlib.blake2b(data, digest_size=16).digest(), data.shape, data.dtype.str


class RecentAnswers(Generic[Answer]):
    """The last ``keep`` answers, by the pixels asked about and the settings they were asked with.

    Parameters
    ----------
    keep : int
        How many answers to keep; the least recently asked goes first.
    """

    def __init__(self, keep: int) -> None:
        self.keep = keep
        self._answers: OrderedDict[tuple, Answer] = OrderedDict()

    def __len__(self) -> int:
        return len(self._answers)

    def get(
        self,
        pixels: Sequence[np.ndarray | None],
        settings: Hashable,
        compute: Callable[[], Answer],
    ) -> Answer:
        """The answer for these pixels and settings: remembered, or ``compute()`` and remembered.

        Parameters
        ----------
        pixels : sequence of ndarray or None
            The arrays the answer depends on (an image, a mask); None for one not given.
        settings : hashable
            Every other argument the answer depends on.
        compute : callable
            Computes the answer when it is not remembered.

        Returns
        -------
        The remembered object itself: the caller returns a copy of it.
        """
        key = (tuple(pixels_key(p) for p in pixels), settings)
        found = self._answers.get(key)
        if found is None:
            found = self._answers[key] = compute()
            while len(self._answers) > self.keep:
                self._answers.popitem(last=False)
        else:
            self._answers.move_to_end(key)
        return found
