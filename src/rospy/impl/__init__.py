"""rospy.impl: the internals of rospy that programs and upstream's tests reach for, as thin
names over kame's runtime (kame.client, kame.node). Its TCPROS, XML-RPC and registration
machinery is kame's; these modules name what user code imports from them."""
