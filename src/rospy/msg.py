"""rospy.msg: AnyMsg (kame.msg.anymsg) and how arguments become a message (kame.client.message_args)."""

from kame.client.message_args import args_kwds_to_message
from kame.msg.anymsg import AnyMsg

__all__ = ["AnyMsg", "args_kwds_to_message"]
